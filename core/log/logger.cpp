#include "core/log/logger.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/sinks/stdout_sinks.h>

#include <iostream>

#include "core/errors.hpp"

namespace suite {

struct Logger::Impl {
  std::shared_ptr<spdlog::logger> log;
};

LogLevel parse_log_level(const std::string& text) {
  if (text == "debug") return LogLevel::debug;
  if (text == "info") return LogLevel::info;
  if (text == "warn") return LogLevel::warn;
  if (text == "error") return LogLevel::error;
  if (text == "off") return LogLevel::off;
  throw InputError(fmt::format("log level '{}' is not valid; use one of debug, info, warn, error, off", text));
}

namespace {
spdlog::level::level_enum to_spd(LogLevel l) {
  switch (l) {
    case LogLevel::debug:
      return spdlog::level::debug;
    case LogLevel::info:
      return spdlog::level::info;
    case LogLevel::warn:
      return spdlog::level::warn;
    case LogLevel::error:
      return spdlog::level::err;
    case LogLevel::off:
      return spdlog::level::off;
  }
  return spdlog::level::info;
}
}  // namespace

Logger::Logger(const mpi::Comm& comm, std::string name, LoggerOptions options)
    : impl_(std::make_unique<Impl>()),
      rank_(comm.rank()),
      size_(comm.size()),
      level_(options.level),
      all_ranks_(options.all_ranks) {
  spdlog::sink_ptr sink;
  if (options.stream != nullptr) {
    sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(*options.stream, true);
  } else {
    sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  }
  // Not registered in spdlog's global registry: each Logger is an ordinary object.
  impl_->log = std::make_shared<spdlog::logger>(std::move(name), sink);
  const std::string rank_tag = size_ > 1 ? fmt::format(" [rank {}]", rank_) : "";
  impl_->log->set_pattern("[%H:%M:%S.%e] [%n]" + rank_tag + " [%l] %v");
  impl_->log->set_level(spdlog::level::trace);
  impl_->log->flush_on(spdlog::level::warn);
}

Logger::~Logger() = default;
Logger::Logger(Logger&&) noexcept = default;
Logger& Logger::operator=(Logger&&) noexcept = default;

void Logger::add_file(const std::filesystem::path& path) {
  auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path.string(), false);
  sink->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%n] [%l] %v");
  impl_->log->sinks().push_back(std::move(sink));
}

void Logger::set_level(LogLevel level) {
  level_ = level;
}

bool Logger::prints(LogLevel level) const {
  if (level < level_ || level == LogLevel::off) return false;
  return level == LogLevel::error || all_ranks_ || rank_ == 0;
}

void Logger::write(LogLevel level, const std::string& message) {
  impl_->log->log(to_spd(level), message);
}

void Logger::flush() {
  impl_->log->flush();
}

}  // namespace suite

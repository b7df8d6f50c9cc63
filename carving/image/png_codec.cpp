#include "carving/image/png_codec.hpp"

#include <fmt/format.h>
#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace suite::carving {
namespace {

// stdio's default 4 KiB buffer made a 400 KiB view a hundred read calls.
constexpr std::size_t kFileBuffer = 1 << 18;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through a callback that must not return: it records the message and
// longjmps back to the setjmp in the caller, which then throws with the file's name. No C++
// object with a destructor is created between the setjmp and a libpng call.
void on_error(png_structp png, png_const_charp message) {
  auto* text = static_cast<std::string*>(png_get_error_ptr(png));
  if (text) *text = message;
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}  // e.g. unknown chunks: the pixels are fine

}  // namespace

std::optional<cv::Mat> read_png_bgr(const std::filesystem::path& path) {
  std::vector<char> buffer(kFileBuffer);  // declared first: it outlives the stream
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw InputError(fmt::format("cannot read image '{}': cannot open it", path.string()));
  std::setvbuf(f.get(), buffer.data(), _IOFBF, buffer.size());
  png_byte signature[8] = {};
  if (std::fread(signature, 1, sizeof signature, f.get()) != sizeof signature ||
      png_sig_cmp(signature, 0, sizeof signature) != 0)
    return std::nullopt;
  std::string error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw LibraryError("libpng: out of memory creating a reader");
  }
  cv::Mat image;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError(
        fmt::format("cannot read image '{}': corrupt or truncated PNG (libpng: {})", path.string(), error));
  }
  png_init_io(png, f.get());
  png_set_sig_bytes(png, sizeof signature);
  png_read_info(png, info);
  const int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
  // The conversions cv::imread(IMREAD_COLOR) makes: 8 bits per channel (16-bit samples keep their
  // high byte), palette and grey expanded to three channels, alpha and transparency dropped,
  // channels in OpenCV's B, G, R order.
  if (depth == 16) png_set_strip_16(png);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if ((type & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if ((type & PNG_COLOR_MASK_COLOR) == 0) png_set_gray_to_rgb(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  png_set_strip_alpha(png);
  png_set_bgr(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const auto width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  if (png_get_rowbytes(png, info) != 3 * static_cast<std::size_t>(width))
    png_error(png, "unexpected row size after conversion to 8-bit BGR");
  image.create(static_cast<int>(height), static_cast<int>(width), CV_8UC3);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) rows[y] = image.ptr<png_byte>(static_cast<int>(y));
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

void write_png_file(const std::filesystem::path& path, const cv::Mat& image, int compression_level) {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw InputError(
        fmt::format("cannot write '{}': give a non-empty 8-bit image of 1 or 3 channels (this one has "
                    "OpenCV type {})",
                    path.string(), image.type()));
  std::vector<char> buffer(kFileBuffer);  // declared first: it outlives the stream
  File f(std::fopen(path.c_str(), "wb"));
  if (!f)
    throw InputError(
        fmt::format("cannot write image '{}': check that the folder exists and is writable", path.string()));
  std::setvbuf(f.get(), buffer.data(), _IOFBF, buffer.size());
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw LibraryError("libpng: out of memory creating a writer");
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.rows));
  for (int y = 0; y < image.rows; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.ptr<png_byte>(y));
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw InputError(fmt::format("cannot write image '{}' (libpng: {}); check the free space", path.string(), error));
  }
  png_init_io(png, f.get());
  // cv::imwrite's defaults: the Sub filter and zlib's run-length strategy, which on photographs
  // compress nearly as well as the adaptive filters with the default strategy in a fraction of
  // the time.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_strategy(png, Z_RLE);
  png_set_compression_level(png, compression_level);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows), 8,
               image.channels() == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (image.channels() == 3) png_set_bgr(png);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(f.get()) != 0 || std::ferror(f.get()))
    throw InputError(fmt::format("cannot write image '{}': the write failed; check the free space", path.string()));
}

}  // namespace suite::carving

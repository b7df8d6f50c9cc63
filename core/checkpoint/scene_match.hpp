#pragma once
// A restart continues the run that wrote the checkpoint only if it runs the same scene. The
// checkpoint keeps the scene as the program read it (config::Config::resolved(): every key with
// its value to the last bit, defaults included), and the restart compares it key by key with the
// scene it was given. Keys that do not change the physics (when to stop, how often to write,
// checkpoint settings) may differ; a solver names them. Any other difference is refused with
// every differing key named, both values side by side.
//
//   checkpoint::SceneRecord rec(cfg);                  // the run's scene
//   writer.write<unsigned char>("scene_keys", rec.bytes());
//   ...
//   const SceneRecord saved = SceneRecord::from_bytes(reader.read<unsigned char>("scene_keys"));
//   saved.require_same(rec, {"time.end", "time.max_steps", "checkpoint"}, "checkpoint 'x.h5'");
#include <map>
#include <string>
#include <vector>

#include "core/config/config.hpp"

namespace suite::checkpoint {

class SceneRecord {
 public:
  explicit SceneRecord(const config::Config& cfg) : keys_(cfg.resolved()) {}
  explicit SceneRecord(std::map<std::string, std::string> keys) : keys_(std::move(keys)) {}

  // "key = value" lines, sorted by key; the form kept in checkpoints and state files.
  std::string text() const;
  std::vector<unsigned char> bytes() const;
  // InputError naming `where` if the text is not such lines.
  static SceneRecord from_text(const std::string& text, const std::string& where);
  static SceneRecord from_bytes(const std::vector<unsigned char>& bytes, const std::string& where);

  const std::map<std::string, std::string>& keys() const { return keys_; }

  // The keys whose values differ between this record (the checkpoint's run) and `now`, present
  // in either, except those `may_change` covers: an entry covers the key equal to it and every
  // key below it ("checkpoint" covers "checkpoint.every"; "inlets" covers "inlets[0].x").
  std::vector<std::string> differences(const SceneRecord& now, const std::vector<std::string>& may_change) const;

  // InputError if differences() is not empty: "<where> was written for another scene: key:
  // A there, B here; ...; restart with the scene it was written with (a restart may change
  // only: ...)".
  void require_same(const SceneRecord& now, const std::vector<std::string>& may_change, const std::string& where) const;

 private:
  std::map<std::string, std::string> keys_;
};

// InputError unless the scene's time.end `end` (s) lies after `time` (s), the time `where` (a
// checkpoint, a saved state) holds: a restart needs steps left to run, and a later end extends
// a finished run.
void require_later_end(double end, double time, const std::string& where);

}  // namespace suite::checkpoint

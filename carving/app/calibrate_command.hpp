#pragma once
// `seedcarve calibrate`: the rig's numbers from calibration photographs (docs/methods/carving.md,
// "Calibration"), written as calibration.json and as camera.yaml lines to paste into a profile.
//   ball IMAGES --diameter MM [--focal PX]     px/mm at the ball and the camera distance
//   chessboard IMAGES --corners CxR --square MM focal length, principal point, distortion
//   axis IMAGES --profile P                    turntable axis column, origin row and base row
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/log/logger.hpp"

namespace suite::carving {

struct CalibrateRequest {
  std::string target;                // ball | chessboard | axis
  std::vector<std::string> images;   // files or folders of images
  std::string profile;               // segmentation (and turntable angles for axis)
  std::vector<std::string> overrides;
  std::optional<double> diameter_mm, focal_px, square_mm;
  std::string corners;               // inner corners "CxR", e.g. 9x6
  std::filesystem::path out;
};

// Runs one calibration; throws InputError for bad arguments or images, naming them.
void run_calibrate(const CalibrateRequest& request, Logger& log);

}  // namespace suite::carving

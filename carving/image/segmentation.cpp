// Seed segmentation by HSV range or Otsu threshold, contour selection and overlays (see segmentation.hpp).
#include "carving/image/segmentation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <system_error>
#include <utility>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

constexpr std::array<int, 3> kChannelMax{180, 255, 255};
constexpr std::array<const char*, 3> kChannelName{"H", "S", "V"};

const char* channel_name(SegmentationOptions::Channel c) {
  switch (c) {
    case SegmentationOptions::Channel::hue:
      return "hue";
    case SegmentationOptions::Channel::saturation:
      return "saturation";
    case SegmentationOptions::Channel::value:
      return "value";
  }
  return "?";
}

void check_options(const SegmentationOptions& o) {
  for (int k = 0; k < 3; ++k) {
    for (const auto& [key, value] : {std::pair{"hsv_low", o.hsv_low[k]}, std::pair{"hsv_high", o.hsv_high[k]}})
      if (value < 0 || value > kChannelMax[k])
        throw InputError(
            fmt::format("segmentation option {} {} = {}; it must lie in 0..{} (OpenCV HSV: H 0..180, S "
                        "and V 0..255)",
                        key, kChannelName[k], value, kChannelMax[k]));
    if (k > 0 && o.hsv_low[k] > o.hsv_high[k])
      throw InputError(fmt::format("segmentation option hsv_low {} = {} is above hsv_high {} = {}; give low <= high",
                                   kChannelName[k], o.hsv_low[k], kChannelName[k], o.hsv_high[k]));
  }
  for (const auto& [key, value] :
       {std::pair{"open_kernel_px", o.open_kernel_px}, std::pair{"close_kernel_px", o.close_kernel_px}})
    if (value < 0 || value > 101)
      throw InputError(fmt::format("segmentation option {} = {}; it must lie in 0..101 px (0 or 1 = off)", key, value));
  if (!(o.min_area >= 0) || !(o.max_area >= o.min_area))
    throw InputError(fmt::format("segmentation options min_area = {}, max_area = {} px; give 0 <= min_area <= max_area",
                                 o.min_area, o.max_area));
}

void morphology(cv::Mat& binary, int operation, int size) {
  if (size <= 1) return;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size));
  cv::morphologyEx(binary, binary, operation, kernel);
}

}  // namespace

Segmentation segment(const cv::Mat& input, const SegmentationOptions& options) {
  check_options(options);
  if (input.empty()) throw InputError("segment: the image is empty (0 x 0 pixels); give a colour photograph");
  if (input.depth() != CV_8U || (input.channels() != 1 && input.channels() != 3 && input.channels() != 4))
    throw InputError(
        fmt::format("segment: the image has {} channel(s) of OpenCV depth {}; give an 8-bit BGR, BGRA or "
                    "grey image",
                    input.channels(), input.depth()));
  cv::Mat bgr = input;
  if (input.channels() == 4) cv::cvtColor(input, bgr, cv::COLOR_BGRA2BGR);
  if (input.channels() == 1) cv::cvtColor(input, bgr, cv::COLOR_GRAY2BGR);
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);

  Segmentation out;
  cv::Mat binary;
  std::string selection;  // how pixels were chosen, for the reason
  if (options.automatic) {
    cv::Mat channel;
    cv::extractChannel(hsv, channel, static_cast<int>(options.otsu_channel));
    const int type = (options.otsu_seed_is_high ? cv::THRESH_BINARY : cv::THRESH_BINARY_INV) | cv::THRESH_OTSU;
    out.threshold = cv::threshold(channel, binary, 0, 255, type);
    selection = fmt::format("{} Otsu's threshold {} on channel {}", options.otsu_seed_is_high ? "above" : "at or below",
                            out.threshold, channel_name(options.otsu_channel));
  } else {
    const auto& lo = options.hsv_low;
    const auto& hi = options.hsv_high;
    if (lo[0] <= hi[0]) {
      cv::inRange(hsv, cv::Scalar(lo[0], lo[1], lo[2]), cv::Scalar(hi[0], hi[1], hi[2]), binary);
    } else {  // a hue range that wraps through 180 -> 0 (reds)
      cv::Mat upper;
      cv::inRange(hsv, cv::Scalar(lo[0], lo[1], lo[2]), cv::Scalar(180, hi[1], hi[2]), binary);
      cv::inRange(hsv, cv::Scalar(0, lo[1], lo[2]), cv::Scalar(hi[0], hi[1], hi[2]), upper);
      binary |= upper;
    }
    selection =
        fmt::format("in the HSV range H [{}, {}], S [{}, {}], V [{}, {}]", lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
  }
  morphology(binary, cv::MORPH_OPEN, options.open_kernel_px);
  morphology(binary, cv::MORPH_CLOSE, options.close_kernel_px);

  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  int chosen = -1;
  double chosen_area = -1, largest_area = -1;
  for (int i = 0; i < static_cast<int>(contours.size()); ++i) {
    const double area = cv::contourArea(contours[i]);
    largest_area = std::max(largest_area, area);
    if (area >= options.min_area && area <= options.max_area && area > chosen_area) chosen = i, chosen_area = area;
  }

  cv::Mat filled = cv::Mat::zeros(bgr.size(), CV_8UC1);
  if (contours.empty()) {
    out.reason = fmt::format("no pixels {} after opening ({} px) and closing ({} px)", selection,
                             options.open_kernel_px, options.close_kernel_px);
  } else if (chosen < 0) {
    out.reason = fmt::format("no contour with area in [{}, {}] px; largest of {} had {} px (pixels {})",
                             options.min_area, options.max_area, contours.size(), largest_area, selection);
  } else {
    out.found = true;
    for (int i = 0; i < static_cast<int>(contours.size()); ++i)
      if (i != chosen) out.other_area = std::max(out.other_area, cv::contourArea(contours[i]));
    out.contour = contours[chosen];
    out.area = chosen_area;
    out.bounding_box = cv::boundingRect(out.contour);
    cv::drawContours(filled, contours, chosen, cv::Scalar(255), cv::FILLED);
  }
  out.mask = mask_from_image(filled);
  return out;
}

Segmentation segment_file(const std::filesystem::path& path, const SegmentationOptions& options) {
  return segment(read_image(path), options);
}

void write_overlay(const std::filesystem::path& path, const cv::Mat& bgr, const Segmentation& segmentation,
                   const std::vector<OverlayLine>& lines) {
  if (bgr.empty()) throw InputError(fmt::format("cannot write overlay '{}': the image is empty", path.string()));
  cv::Mat canvas;
  if (bgr.channels() == 1)
    cv::cvtColor(bgr, canvas, cv::COLOR_GRAY2BGR);
  else if (bgr.channels() == 4)
    cv::cvtColor(bgr, canvas, cv::COLOR_BGRA2BGR);
  else
    canvas = bgr.clone();
  const cv::Scalar green(0, 255, 0), yellow(0, 255, 255), red(0, 0, 255);
  if (segmentation.found) {
    cv::rectangle(canvas, segmentation.bounding_box, yellow, 1);
    cv::drawContours(canvas, std::vector<std::vector<cv::Point>>{segmentation.contour}, 0, green, 1);
  } else {
    cv::putText(canvas, segmentation.reason, cv::Point(5, 15), cv::FONT_HERSHEY_SIMPLEX, 0.4, red, 1, cv::LINE_AA);
  }
  constexpr int shift = 4;  // sub-pixel line ends: coordinates in 1/16 px
  const auto fixed = [](const cv::Point2d& p) { return cv::Point(cvRound(p.x * 16), cvRound(p.y * 16)); };
  for (const auto& line : lines) cv::line(canvas, fixed(line.from), fixed(line.to), red, 1, cv::LINE_8, shift);
  write_png(path, canvas);
}

double intersection_over_union(const Mask& a, const Mask& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw InputError(fmt::format("intersection_over_union: masks of {} x {} and {} x {} px; give masks of one size",
                                 a.width(), a.height(), b.width(), b.height()));
  long long both = 0, either = 0;
  const auto& pa = a.pixels();
  const auto& pb = b.pixels();
  for (std::size_t i = 0; i < pa.size(); ++i) {
    both += pa[i] & pb[i];
    either += pa[i] | pb[i];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

}  // namespace suite::carving

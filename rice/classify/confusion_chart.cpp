#include "rice/classify/confusion_chart.hpp"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "rice/measure/image_files.hpp"

namespace suite::rice {
namespace {

constexpr int kCell = 96, kLeft = 130, kTop = 110, kGap = 60, kBottom = 40;
const cv::Scalar kInk(40, 40, 40);

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour, int thickness,
          bool centred) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &base);
  if (centred) at -= cv::Point(size.width / 2, -size.height / 2);
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

void draw_panel(cv::Mat& image, int x0, const ConfusionPanel& panel) {
  const Confusion& m = panel.confusion;
  const int n = static_cast<int>(m.classes.size());
  const double accuracy = m.accuracy();
  text(image, panel.title, {x0, 32}, 0.75, kInk, 2, false);
  text(image,
       std::isfinite(accuracy) ? fmt::format("accuracy {:.1f}% of {} grains", 100 * accuracy, m.total())
                               : std::string("no grains"),
       {x0, 62}, 0.6, kInk, 1, false);
  text(image, "predicted", {x0 + kLeft + n * kCell / 2, kTop - 12}, 0.55, kInk, 1, true);
  for (int t = 0; t < n; ++t) {
    long row = 0;
    for (long c : m.counts[static_cast<std::size_t>(t)]) row += c;
    text(image, "true " + m.classes[static_cast<std::size_t>(t)], {x0 + 8, kTop + t * kCell + kCell / 2 + 5}, 0.55,
         kInk, 1, false);
    for (int p = 0; p < n; ++p) {
      const long count = m.counts[static_cast<std::size_t>(t)][static_cast<std::size_t>(p)];
      const double share = row > 0 ? static_cast<double>(count) / static_cast<double>(row) : 0.0;
      // White to dark blue (BGR) with the share; text turns white on dark cells.
      const cv::Scalar fill(255 - 75 * share, 255 - 200 * share, 255 - 230 * share);
      const cv::Rect cell(x0 + kLeft + p * kCell, kTop + t * kCell, kCell, kCell);
      cv::rectangle(image, cell, fill, cv::FILLED);
      cv::rectangle(image, cell, {180, 180, 180}, 1);
      const cv::Scalar ink = share > 0.55 ? cv::Scalar(255, 255, 255) : kInk;
      const cv::Point centre(cell.x + kCell / 2, cell.y + kCell / 2);
      text(image, std::to_string(count), centre - cv::Point(0, 10), 0.75, ink, 2, true);
      if (row > 0) text(image, fmt::format("{:.0f}%", 100 * share), centre + cv::Point(0, 20), 0.5, ink, 1, true);
    }
  }
  for (int p = 0; p < n; ++p)
    text(image, m.classes[static_cast<std::size_t>(p)], {x0 + kLeft + p * kCell + kCell / 2, kTop + n * kCell + 22},
         0.55, kInk, 1, true);
}

}  // namespace

void draw_confusion_chart(const std::filesystem::path& png, const std::vector<ConfusionPanel>& panels) {
  int n = 1;
  for (const auto& p : panels) n = std::max(n, static_cast<int>(p.confusion.classes.size()));
  const int panel_width = kLeft + n * kCell + kGap;
  cv::Mat image(kTop + n * kCell + kBottom, std::max(1, static_cast<int>(panels.size())) * panel_width, CV_8UC3,
                cv::Scalar(255, 255, 255));
  for (std::size_t i = 0; i < panels.size(); ++i) draw_panel(image, static_cast<int>(i) * panel_width + 10, panels[i]);
  write_png(png, image);
}

}  // namespace suite::rice

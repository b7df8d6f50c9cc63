#include "benchmarks/carving/two_view_speed.hpp"

#include <numbers>
#include <stdexcept>
#include <vector>

#include "benchmarks/carving/bench_support.hpp"
#include "carving/image/segmentation.hpp"
#include "carving/render/renderer.hpp"
#include "carving/slicing/two_view.hpp"

namespace suite::carving::bench {

TwoViewTiming time_two_view(int batches, int per_batch) {
  constexpr double kPxPerMm = 40;
  // The top camera looks down the turntable (y) axis, the side camera horizontally; the seed's
  // long axis runs along the image rows in both (as render_scene's two-view rig).
  const Eigen::Matrix3d top_r = rotation_matrix(Eigen::Vector3d::UnitX(), std::numbers::pi / 2);
  const View top{parallel_projection(kPxPerMm, 320, 240, top_r), 640, 480};
  const View side{parallel_projection(kPxPerMm, 320, 240, Eigen::Matrix3d::Identity()), 640, 480};
  const Ellipsoid seed(3.6, 1.8, 1.45);
  RenderOptions photo;
  photo.supersampling = 2;
  photo.blur_sigma_px = 0.7;
  photo.noise_sigma = 2;
  photo.noise_seed = 4;
  const cv::Mat top_image = render(seed, top, photo).image;
  photo.noise_seed = 5;
  const cv::Mat side_image = render(seed, side, photo).image;

  const SegmentationOptions segmentation;  // the defaults: wheat HSV range, 15,000-50,000 px
  SlicingOptions slicing;
  slicing.px_per_mm_top = kPxPerMm;
  TwoViewTiming t;
  t.batches = batches, t.per_batch = per_batch;
  t.true_mm3 = seed.volume();

  // Check once that both images segment, so the timed loop measures real work.
  const Segmentation a = segment(top_image, segmentation), b = segment(side_image, segmentation);
  if (!a.found || !b.found) throw std::runtime_error("two-view benchmark: segmentation failed: " + a.reason + b.reason);
  t.volume_mm3 = measure_two_view(a.mask, b.mask, slicing).volume_mm3;

  double sink = 0;  // keeps the compiler from dropping the timed work
  const auto pairs = time_repeats(batches, [&] {
    for (int i = 0; i < per_batch; ++i) {
      const Segmentation s_top = segment(top_image, segmentation);
      const Segmentation s_side = segment(side_image, segmentation);
      sink += measure_two_view(s_top.mask, s_side.mask, slicing).volume_mm3;
    }
  });
  const auto segments = time_repeats(batches, [&] {
    for (int i = 0; i < per_batch; ++i) sink += segment(top_image, segmentation).area;
  });
  const auto slices = time_repeats(batches, [&] {
    for (int i = 0; i < per_batch; ++i) sink += measure_two_view(a.mask, b.mask, slicing).volume_mm3;
  });
  if (sink < 0) throw std::runtime_error("impossible");
  t.pair_s = median(pairs) / per_batch;
  t.segment_s = median(segments) / per_batch;
  t.slicing_s = median(slices) / per_batch;
  return t;
}

}  // namespace suite::carving::bench

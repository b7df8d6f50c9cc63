#pragma once
// Two-view slicing speed: a top and a side photograph of a wheat-sized ellipsoid (the rig of
// carving/examples/synthetic/wheat_two_view.yaml: parallel cameras, 40 px/mm, 640 x 480 px,
// blur 0.7 px, noise 2 grey levels) are rendered once; then segmentation of both colour images
// and the 50-slice model are timed over many repeats on one core.
namespace suite::carving::bench {

struct TwoViewTiming {
  double pair_s = 0;      // median seconds per pair: segment(top) + segment(side) + measure_two_view
  double segment_s = 0;   // median seconds to segment one image
  double slicing_s = 0;   // median seconds of measure_two_view on the two masks
  double volume_mm3 = 0;  // the model's answer on the segmented masks
  double true_mm3 = 0;    // the ellipsoid's volume
  int batches = 0, per_batch = 0;
};

// `batches` timed batches of `per_batch` pairs each; the medians are over the batches.
TwoViewTiming time_two_view(int batches, int per_batch);

}  // namespace suite::carving::bench

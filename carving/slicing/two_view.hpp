#pragma once
// The two-view slicing model of docs/methods/carving.md: a seed's volume from a top-view and a side-view
// silhouette, as a stack of N elliptic slices.
//
// Conventions:
// - The seed lies with its long axis along the image x axis (columns) in BOTH views; the top
//   view's y extent is the seed's width and the side view's y extent its thickness. The masks are
//   taken in that fixed orientation (an axis-aligned bounding box; no rotation to principal axes).
// - Each mask holds one seed (e.g. Segmentation::mask, the filled chosen contour).
// - Length X_top, X_side: from tip to tip along the columns in each view, each tip found between
//   the last column with seed pixels and the next from the chord lengths h of the last two columns
//   (a rounded tip: h^2 falls linearly to 0 at it; half a pixel beyond the last column where h does
//   not fall), so that a seed whose tips fall on pixel centres is not read a pixel long, as counting
//   columns did. The side camera can sit at a different distance, so its pixels are rescaled by
//   s = X_top / X_side (the length both cameras see); the side view's pixel size is then
//   px_per_mm_top / s.
// - The top view's length is cut into N equal slices of h = length / N. Slice i's centre lies at
//   c_i = t0 + (i + 1/2) X_top / N (columns have their centres at integers, t0 the first tip). A_i is half the top
//   view's seed-pixel count of column c_i and B_i half the side view's count at the corresponding position t0_side +
//   (c_i - t0) / s, both linearly interpolated between the two nearest columns (columns outside the seed count 0), so
//   the width is taken at the slice centre, not maximised over the slice (that biases the volume up ~3%). v_i = pi A_i
//   B_i h, V = sum v_i: the midpoint rule for the integral of the ellipse areas, whose error falls as 1/N^2 for a
//   smooth profile (for an ellipsoid it is exactly +1/(2 N^2) of V).
// - Reported width and thickness are the extents of the masks across (tip to tip along the rows,
//   as the length; the side view's rescaled by s), like caliper readings, not the maxima of 2 A_i,
//   2 B_i. Volume: the midpoint rule's +1/(2 N^2) soon falls below the chords' pixel quantisation,
//   and more slices buy nothing from there (docs/methods/carving.md, step 3, has the numbers).
// - Without scale correction s = 1: the side view is taken to have the top view's pixel size.
// - neighbour_average (the dissertation's smoothing, off by default): a column's chord is no longer
//   its seed-pixel count but the distance between its upper and lower contour points (first and
//   last seed rows, plus one pixel), each averaged over 5 adjacent columns: the column itself and
//   two on each side (those with seed pixels; fewer at the tips). It is applied in both views before
//   the slices' widths are interpolated. It acts as a 5 px box filter: on a smooth convex outline
//   it lowers a concave chord profile by about w''(x) px^2 (an ellipsoid of half length L px by
//   about 1.5 ln(L) / L^2 of its volume; docs/carving.md has the measured effect and when to use
//   it), and a one-column spike reaches a slice at a fifth of its height; the lengths, widths and
//   thicknesses reported are unchanged.
#include <vector>

#include "carving/image/mask.hpp"

namespace suite::carving {

struct SlicingOptions {
  int slices = 50;           // N, 1..100000
  double px_per_mm_top = 0;  // top-view pixels per mm (from a reference ball); required, > 0
  bool scale_correction = true;
  bool neighbour_average = false;  // average each column's contour points with 2 columns on each side
};

struct Slice {
  double top_x_px = 0;    // slice centre in the top view (column coordinate)
  double side_x_px = 0;   // the corresponding position in the side view
  double a_mm = 0;        // A_i: half the width at the slice centre
  double b_mm = 0;        // B_i: half the thickness at the slice centre
  double h_mm = 0;        // h_i: slice length
  double volume_mm3 = 0;  // pi A_i B_i h_i
};

// Inclusive pixel bounds of a mask's seed pixels.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

struct TwoViewResult {
  double length_mm = 0;
  double width_mm = 0;
  double thickness_mm = 0;
  double volume_mm3 = 0;
  double scale = 1;           // s = X_top / X_side (1 without scale correction)
  double px_per_mm_side = 0;  // px_per_mm_top / s
  PixelBox top_box, side_box;
  std::vector<Slice> slices;
};

// InputError when a mask is empty or an option is out of range (the message names which).
TwoViewResult measure_two_view(const Mask& top, const Mask& side, const SlicingOptions& options);

// Density in mg/mm^3 from a weight in mg; InputError unless both are positive and finite.
double density_mg_per_mm3(double weight_mg, double volume_mm3);

}  // namespace suite::carving

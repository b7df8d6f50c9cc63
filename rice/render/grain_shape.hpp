#pragma once
// One rice grain in alkali as the renderer draws it (docs/rice.md, "The renderer"): the random
// draws of its appearance (GrainSpec), its layers on a local canvas (kernel and gel masks drawn with
// OpenCV's fillPoly and line), and the ground truth measured on those masks before any blur or noise.
//
// Coordinates: pixels, x right, y down; a pixel's centre is at integer (x, y). The kernel is a
// superellipse |x/a|^n + |y/b|^n = 1 with n = kRiceExponent (a rounded oblong like a milled grain),
// its long axis at `angle_deg` from the image's x axis. The collar is the same outline grown by the
// collar width on both axes; an incomplete collar is the sector of it between two parametric angles.
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

namespace suite::rice {

constexpr double kRiceExponent = 2.4;

// An extra ellipse of gel: a lobe of a grade-6 collar or of a grade-7 cloud; offsets and axes in mm
// in the grain's frame (x along the long axis).
struct GelLobe {
  double dx_mm = 0, dy_mm = 0, half_length_mm = 0, half_width_mm = 0, angle_deg = 0;
};

struct GrainSpec {
  int grade = 2;
  cv::Point2d centre_px;                 // the kernel's centre in the image
  double angle_deg = 0;                  // long axis from the image's x axis
  double length_mm = 6, width_mm = 2.2;  // the kernel (swollen); grade 7: the grain it was
  double collar_mm = 0;                  // gel band width beyond the kernel; 0: no collar
  double collar_start_deg = 0;           // incomplete collar: parametric start angle on the outline
  double collar_span_deg = 360;          // parametric span; 360: complete
  std::vector<double> cracks;            // grade 5: crack positions along the long axis, in half lengths (-1..1)
  std::vector<double> crack_tilts_deg;
  double crack_mm = 0;                                       // crack width
  double remnant_scale_length = 1, remnant_scale_width = 1;  // grade 6: remnant size / kernel size
  double remnant_dx_mm = 0, remnant_dy_mm = 0;               // grade 6: remnant offset in the grain frame
  std::vector<GelLobe> lobes;                                // grade 6: extra gel lobes; grade 7: the cloud
  double kernel_level = 215;                                 // grey level of an intact kernel (0..255, before lighting)
  double kernel_fraction = 1;     // grade 6: the remnant's level as a fraction of kernel_level
  double gel_level = 95;          // grey level of the gel
  double gel_texture = 0.06;      // relative amplitude of the gel's low-frequency texture
  double kernel_edge_mm = 0.014;  // Gaussian sigma of the kernel's edge
  double gel_edge_mm = 0.02;      // Gaussian sigma of the gel's outer edge
  std::uint64_t texture_seed = 1;
  bool touching = false;  // drawn against a neighbour (the truth says so)
};

// Random appearance of one grain of `grade` at `centre_px` (Little et al.'s scale, grade_scale.hpp).
GrainSpec random_grain(int grade, cv::Point2d centre_px, std::mt19937_64& rng);

// Half the side of a square that holds the grain with its blurred edges, mm.
double grain_reach_mm(const GrainSpec& spec);

struct GrainLayers {
  cv::Point origin;   // image pixel of the canvas's top-left corner
  cv::Mat kernel;     // CV_8U, 255 = kernel (or grade-6 remnant)
  cv::Mat gel;        // CV_8U, 255 = gel drawn (also under the kernel)
  cv::Mat gel_level;  // CV_32F, the gel's grey level per pixel (texture and the remnant's halo)
};

// The grain's layers on a canvas around it; `mm_per_px` is the pixel size.
GrainLayers draw_grain(const GrainSpec& spec, double mm_per_px);

// Ground truth of one grain, from its layers before blur and noise.
struct GrainTruth {
  double kernel_area_mm2 = 0;
  double gel_area_mm2 = 0;         // gel not covered by the kernel
  double gel_kernel_ratio = 0;     // NaN without a kernel
  double collar_completeness = 0;  // fraction of directions from the kernel centre with gel (grade 7: 1)
  int kernel_pieces = 0;
  double kernel_share = 0;  // the kernel's share of the grain's brightness above the dish
};

GrainTruth grain_truth(const GrainSpec& spec, const GrainLayers& layers, double mm_per_px, double dish_level);

// The outline of a superellipse with half axes (a, b) px, rotated by angle_deg about `centre`,
// at parametric angles from start_deg over span_deg (points every 1 degree or finer).
std::vector<cv::Point2d> superellipse_outline(cv::Point2d centre, double a, double b, double angle_deg,
                                              double start_deg = 0, double span_deg = 360);

// Fraction of directions from `centre` that the parametric sector [start, start + span] of the
// outline covers (the polar angle swept by its points), in [0, 1].
double sector_coverage(double a, double b, double start_deg, double span_deg);

}  // namespace suite::rice

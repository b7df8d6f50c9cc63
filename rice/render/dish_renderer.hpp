#pragma once
// One synthetic photograph of grains in alkali on a black dish, seen from above (docs/rice.md,
// "The renderer"): grains laid out on a grid of cells with random offsets, each drawn by
// grain_shape.hpp and composited (gel over the dish, kernel over the gel, edges softened with
// Gaussian blurs), then a lighting gradient, the optics' blur and sensor noise. Grey levels are
// 0..255; the image is BGR with a faint warm tint (a white lamp on chalky grains).
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "rice/render/grain_shape.hpp"

namespace suite::rice {

struct DishOptions {
  double mm_per_px = 0.02;          // pixel size
  int columns = 3;                  // cells per row
  double cell_mm = 16;              // side of each grain's cell
  double dish_level = 18;           // grey level of the black dish
  double lighting_gradient = 0.10;  // largest relative change of the light from the centre to an edge
  double blur_mm = 0.02;            // Gaussian sigma of the optics
  double noise_sigma = 4;           // sensor noise, grey levels per channel
  int touching_pairs = 0;           // cells that hold two grains side by side, touching (grades 2-5 only)
  bool frame_cut = false;           // move the last grain across the right edge of the frame
};

struct RenderedGrain {
  int index = 0;  // 1, 2, ... within its image, in the order of the cells
  GrainSpec spec;
  GrainTruth truth;
  bool cut_by_frame = false;
};

struct RenderedDish {
  cv::Mat image;  // CV_8UC3 BGR
  std::vector<RenderedGrain> grains;
};

// Renders one grain of each entry of `grades` (each 2..7). InputError for options out of range
// (naming the option) or no grades.
RenderedDish render_dish(const std::vector<int>& grades, const DishOptions& options, std::mt19937_64& rng);

}  // namespace suite::rice

#pragma once
// The alkali spreading value (ASV) scale of Little, Hilder and Dawson (1958, Cereal Chemistry 35:
// 111-126) and how the renderer draws each grade. Milled grains soaked in 1.7% KOH for 23 h at 30 C
// are scored from 2 to 7:
//   2  kernel swollen, not spread (no collar)
//   3  kernel swollen, collar incomplete or narrow
//   4  kernel swollen, collar complete and wide
//   5  kernel split or segmented, collar complete and wide
//   6  kernel dispersed, merging with the collar
//   7  kernel completely dispersed and intermingled (no kernel left, a diffuse cloud)
// (grade 1, "kernel not affected", is not drawn: it looks like grade 2 without swelling).
// The ranges below are the renderer's choices, read off the scale's descriptions and typical
// photographs; lengths in mm, fractions in [0, 1]. docs/rice.md lists them.
#include <string>

namespace suite::rice {

constexpr int kLowestGrade = 2;
constexpr int kHighestGrade = 7;

struct Range {
  double low = 0, high = 0;
};

struct GradeAppearance {
  int grade = 0;
  std::string description;             // the scale's words
  Range swelling;                      // kernel length and width times this (soaked grains swell)
  Range collar_width_mm;               // gel band beyond the kernel outline; {0, 0}: no collar
  Range collar_completeness;           // fraction of directions around the kernel with gel
  double narrow_share = 0;             // grade 3: share of grains whose collar is complete but narrow
  Range narrow_width_mm;               // grade 3: the narrow collar's width
  int min_pieces = 1, max_pieces = 1;  // kernel pieces (grade 5: split; 0: no kernel)
  Range crack_width_mm;                // grade 5: the gel-filled gaps between pieces
  Range remnant_scale;                 // grade 6: the kernel remnant's length and width as a fraction of the kernel's
  Range remnant_level;                 // grade 6: the remnant's brightness as a fraction of an intact kernel's
  Range cloud_radius_mm;               // grade 7: the cloud's lobes reach this far beyond the kernel's half length
};

// The appearance of `grade`; InputError unless 2 <= grade <= 7.
const GradeAppearance& appearance(int grade);

}  // namespace suite::rice

#pragma once
// Finite-element erosion of the dam surface (docs/methods/foam_erosion_fem.md step 6).
//
// The surface is a SurfaceCurve of linear (P1) elements. One coupling step:
// 1. Erosion rate per element from its bed shear stress, e = kd (tau - tau_c)^+ (m/s).
// 2. L2 projection of the element-constant rates onto the P1 nodal basis (project_to_nodes).
// 3. Every interior node moves into the soil by d_i = e_i dt f_morph (see NodeMotion for the
//    direction and the corner factor), truncated at the non-erodible foundation level.
// 4. Validity: no self-intersection, no element shorter than min_element_length, no element that
//    turns back on itself. Where a move is invalid the step is split into 2, 4, ... substeps
//    (normals recomputed from the current curve each substep, nodal rates kept); if it is still
//    invalid at max_substeps, erode throws CurveValidityError naming the element.
// 5. Optional angle-of-repose limiter (limit_repose): sand slides on steep elements, area kept.
//
// Fixed topology: the node count never changes (the coupling maps the flow's wall shear onto
// these elements and cuts the flow mesh along the curve, coupling/ and case/dam_cells.hpp).
// The two end nodes never move: they are where the dam surface meets the non-erodible floor.
//
// Bookkeeping: ErosionStepReport::eroded_area is the exact polygon area between the old and the
// new curve; rate_integral is dt f_morph times the exact integral of the nodal rate (P1
// interpolant) over the old curve. They agree to first order in dt except for the half elements
// at the two pinned end nodes (pinned_end_integral), foundation clamping and the repose limiter's
// untouchable elements; the difference of a sum over steps shrinks like dt.
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/foam_erosion_fem/erosion/surface_curve.hpp"

namespace suite::foam_erosion {

// Linear excess-shear-stress law (Partheniades 1965; Hanson & Cook 2004).
struct ErosionLaw {
  double kd = 0;     // erodibility, m^3/(N s) == m/(s Pa)
  double tau_c = 0;  // critical shear stress, Pa
  // Erosion rate normal to the surface, m/s.
  double rate(double tau) const { return tau > tau_c ? kd * (tau - tau_c) : 0.0; }
};

// L2 projection of element-constant values onto P1 nodal values.
//  lumped:     row-sum (lumped) mass matrix, M_ii = (L_{i-1} + L_i) / 2: the nodal value is the
//              length-weighted average of the adjacent element values. Bounded by them, so a
//              non-negative field stays non-negative. Default.
//  consistent: the consistent P1 mass matrix (tridiagonal, M_ii = (L_{i-1} + L_i) / 3,
//              M_i,i+1 = L_i / 6), solved exactly. Galerkin orthogonality keeps every P1 moment
//              (integral, first moment) of the data, but it over/undershoots at jumps, so a
//              nodal value can be negative next to a jump in stress (the node then moves out).
// Both keep the integral: sum_i M_lumped_ii u_i = integral of the P1 field = sum_e L_e f_e.
enum class Projection { lumped, consistent };

// The direction and length of a node's move, given its depth d_i = e_i dt f_morph and
// m_i = (L_{i-1} n_{i-1} + L_i n_i) / (L_{i-1} + L_i) (|m_i| <= 1, cos(theta/2) at a corner of
// turning angle theta between equal elements):
//  area_consistent: move by d_i / |m_i| along -m_i / |m_i|. To first order the swept area is
//                   then exactly sum_i M_lumped_ii d_i, the integral of the P1 depth, also at
//                   corners; a corner between two faces eroding at the same rate moves like
//                   the parallel offset of both faces. The factor 1/|m_i| is capped at 4. Default.
//  unit_normal:     move by d_i along the unit nodal normal. At a corner this sweeps only
//                   |m_i| of the integral, an error that does not shrink with dt.
// The two agree on a straight curve.
enum class NodeMotion { area_consistent, unit_normal };

struct ErosionSettings {
  ErosionLaw law;
  double morphological_factor = 1;  // f_morph: multiplies every move (morphological acceleration)
  double min_element_length = 0;    // m; a move may not leave an element shorter (0: only > 0)
  // m; non-erodible: no node moves below it (default: no foundation).
  double foundation_level = -std::numeric_limits<double>::infinity();
  std::optional<double> repose_angle_deg;  // angle-of-repose limiter, degrees in (0, 90); off if empty
  Projection projection = Projection::lumped;
  NodeMotion motion = NodeMotion::area_consistent;
  int max_substeps = 64;  // substeps double from 1 up to this before erode gives up
};

struct ErosionStepReport {
  double eroded_area = 0;           // m^2 per unit width: exact polygon area between old and new curve
  double rate_integral = 0;         // m^2 per unit width: dt f_morph * integral of the nodal rate over the old curve
  double pinned_end_integral = 0;   // m^2: the part of rate_integral on the half elements at the two fixed end nodes
  double max_depth = 0;             // m: largest node displacement of this step
  int nodes_clamped = 0;            // nodes whose motion the foundation level truncated
  int nodes_limited_by_repose = 0;  // nodes the repose limiter moved
  int repose_elements_left = 0;     // elements still steeper than the repose angle (see limit_repose)
  int substeps = 1;                 // substeps the move needed
};

// A curve that erode cannot keep valid. element() is the offending element (-1 if none applies).
class CurveValidityError : public std::runtime_error {
 public:
  CurveValidityError(const std::string& what, int element) : std::runtime_error(what), element_(element) {}
  int element() const { return element_; }

 private:
  int element_;
};

// Lumped P1 mass (m) per node: M_ii = (L_{i-1} + L_i) / 2, with the missing element 0 at the ends.
std::vector<double> lumped_mass(const SurfaceCurve& curve);

// Exact integral over the curve of the P1 interpolant of nodal values (the trapezoid rule).
double integrate_nodal(const SurfaceCurve& curve, const std::vector<double>& nodal_values);

// Nodal values (one per node) of the L2 projection of element-constant values (one per element).
// Throws std::invalid_argument on a size mismatch or an element of zero length.
std::vector<double> project_to_nodes(const SurfaceCurve& curve, const std::vector<double>& element_values,
                                     Projection projection = Projection::lumped);

struct ReposeResult {
  int nodes_moved = 0;    // nodes whose height changed
  int elements_left = 0;  // elements still steeper than the angle (tolerance included)
  int sweeps = 0;         // Gauss-Seidel sweeps used
};

// Angle-of-repose limiter: sand slides down every element steeper than tan(angle) relative to the
// horizontal. For such an element the upper node is lowered by a and the lower node raised by b,
// a + b bringing the element exactly to the angle, with a w_upper = b w_lower where
// w_i = (x_{i+1} - x_{i-1}) / 2 is the node's horizontal tributary width: the area under the
// curve changes by -a w_upper + b w_lower = 0 exactly, so the eroded area is untouched (round-off
// aside). Nodes move vertically only. Sweeps alternate direction until no element exceeds the
// angle by more than 1e-9 relative, or max_sweeps. Elements the limiter cannot relax are left and
// counted in elements_left: those touching a fixed end node (the sand would have to leave the
// curve) and those whose x extent or node tributary widths are not positive (vertical or
// overhanging parts, where vertical moves cannot reach the angle).
ReposeResult limit_repose(SurfaceCurve& curve, double repose_angle_deg, int max_sweeps = 20000);

// One erosion step of length dt (s) under the bed shear stress of each element (Pa), in place.
// Throws std::invalid_argument for bad arguments or settings and CurveValidityError if the
// incoming curve is invalid or no substep count up to max_substeps keeps it valid (the message
// names the element and the reason); the curve is then left unchanged.
ErosionStepReport erode(SurfaceCurve& curve, const std::vector<double>& element_shear, double dt,
                        const ErosionSettings& settings);

}  // namespace suite::foam_erosion

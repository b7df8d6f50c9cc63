#pragma once
// Headcut advance by jet scour and mass failure of the face (docs/methods/breach.md, stage II), the
// deterministic picture of Hanson, Robinson & Cook (2001) and Temple et al. (2005):
//
// 1. The overfall. Flow of unit discharge q leaves the brink at critical depth y_c = (q^2/g)^(1/3)
//    and falls the headcut height H as a plane jet reaching the tailwater with velocity
//    U0 = sqrt(g y_c + 2 g H) and thickness y0 = q / U0. The tailwater below the headcut is
//    taken at critical depth, y_t = y_c (an assumption: the flow leaves the plunge pool through
//    a critical section).
// 2. Jet stress at distance J below the tailwater surface (plane jet; Stein, Julien & Alonso 1993,
//    J. Hydraul. Res. 31(6), as used by Alonso, Bennett & Stein 2002, WRR 38(12)):
//      tau_j = C_f rho U0^2             for J <= J_p = C_d y0 (potential core)
//      tau_j = C_f rho U0^2 (J_p / J)   beyond it,
//    with C_f = 0.025 and C_d = 2.6 from those papers (inputs: jet_friction, jet_diffusion).
//    The scour hole deepens at the excess-stress rate kd (tau_j - tau_c).
// 3. Mass failure. An unsupported vertical face of undrained strength s_u and unit weight
//    gamma_t stands up to H_c = N s_u / gamma_t, N = 3.85 (Taylor 1948, stability number of a
//    vertical cut with phi = 0; 2.67 with a tension crack, Terzaghi 1943): input
//    critical_height_factor. The face fails when headcut height + scour depth reaches H_c, along
//    the 45-degree plane of a phi = 0 soil (Culmann), so a block as wide as the failing height
//    drops: dX = H + d_c with d_c = max(H_c - H, 0) the scour needed.
// 4. Advance rate. One cycle is the scour time T_s from 0 to d_c (closed form below) plus the
//    time the jet needs to undercut the block's width at the base rate r_0 = kd (tau_j(y_t) -
//    tau_c):  dX/dt = dX / (T_s + dX / r_0). A face taller than H_c fails as fast as it is
//    undercut (dX/dt = r_0); a scour hole that cannot reach d_c before its stress falls to tau_c
//    leaves the headcut stalled (dX/dt = 0). The rate is continuous in q and H, so the ODE
//    integrator sees a smooth right-hand side.
// The combination of 3 and 4 into one rate is this suite's assumption: WinDAM C's closed form is
// not published in the sources at hand (see the closing note of issue 5).
namespace suite::breach {

struct Soil;

struct HeadcutCoefficients {
  double jet_friction = 0.025;           // C_f (Stein et al. 1993)
  double jet_diffusion = 2.6;            // C_d (Stein et al. 1993)
  double critical_height_factor = 3.85;  // N (Taylor 1948)
};

// Jet stress (Pa) at depth J (m) below the tailwater surface, for unit discharge q and drop H.
double jet_stress(double unit_discharge, double drop, double depth, const HeadcutCoefficients& c, double gravity);

// Time (s) for the scour hole below the overfall to deepen from depth d0 to d1 (m); +infinity
// if the jet cannot get there (its stress falls to tau_c first).
double scour_time(double unit_discharge, double drop, double d0, double d1, const Soil& soil,
                  const HeadcutCoefficients& c, double gravity);

// Headcut advance rate (m/s) of item 4.
double headcut_advance_rate(double unit_discharge, double headcut_height, const Soil& soil,
                            const HeadcutCoefficients& c, double gravity);

}  // namespace suite::breach

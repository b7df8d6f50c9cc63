#include "solvers/foam_erosion_fem/case/case_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solvers/foam_erosion_fem/case/block_mesh_dict.hpp"
#include "solvers/foam_erosion_fem/case/foam_file.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

std::string num(double v) { return foam_number(v); }

bool turbulent(const FoamScene& s) { return s.flow.turbulence == "kEpsilon"; }

// One boundaryField entry per patch, from (patch, body) pairs; frontAndBack is always empty.
std::string boundary_field(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string out = "boundaryField\n{\n";
  for (const auto& [patch, body] : entries) out += fmt::format("    {}\n    {{\n{}    }}\n", patch, body);
  out += "    frontAndBack\n    {\n        type empty;\n    }\n}\n";
  return out;
}

std::string field_file(const std::string& cls, const std::string& name, const std::string& dims,
                       const std::string& internal, const std::vector<std::pair<std::string, std::string>>& patches) {
  return foam_header(cls, name, "0") + fmt::format("dimensions      {};\n\ninternalField   {};\n\n", dims, internal) +
         boundary_field(patches);
}

// Initial turbulence: 5% intensity of the free-fall velocity over the dam height, mixing length
// a tenth of the dam height (small against the flow, which sets its own levels within steps).
struct TurbulenceInit {
  double k, epsilon;
};
TurbulenceInit turbulence_init(const FoamScene& s) {
  const double u = std::sqrt(2.0 * s.gravity * s.dam.height);
  const double k = 1.5 * std::pow(0.05 * u, 2);
  const double epsilon = std::pow(0.09, 0.75) * std::pow(k, 1.5) / (0.1 * s.dam.height);
  return {k, epsilon};
}

}  // namespace

void write_initial_fields(const FoamScene& s, const SectionLayout& L, const fs::path& dir) {
  const std::string flow_rate = inlet_flow_rate(s, L);
  const std::string zero_vec = "uniform (0 0 0)";
  const std::string wall_u = "        type            noSlip;\n";
  write_case_file(dir, "0/U",
                  field_file("volVectorField", "U", "[0 1 -1 0 0 0 0]", zero_vec,
                             {{"inlet", fmt::format("        type            variableHeightFlowRateInletVelocity;\n"
                                                    "        alpha           alpha.water;\n"
                                                    "        flowRate        {};\n"
                                                    "        value           uniform (0 0 0);\n",
                                                    flow_rate)},
                              {"outlet", "        type            inletOutlet;\n        inletValue      uniform (0 0 0);\n"
                                         "        value           uniform (0 0 0);\n"},
                              {"atmosphere", "        type            pressureInletOutletVelocity;\n"
                                             "        value           uniform (0 0 0);\n"},
                              {"floor", wall_u},
                              {"dam", wall_u}}));
  const std::string bounded = "        type            variableHeightFlowRate;\n        lowerBound      0;\n"
                              "        upperBound      0.9;\n        value           uniform 0;\n";
  write_case_file(dir, "0/alpha.water",
                  field_file("volScalarField", "alpha.water", "[0 0 0 0 0 0 0]", "uniform 0",
                             {{"inlet", bounded},
                              {"outlet", bounded},
                              {"atmosphere", "        type            inletOutlet;\n        inletValue      uniform 0;\n"
                                             "        value           uniform 0;\n"},
                              {"floor", "        type            zeroGradient;\n"},
                              {"dam", "        type            zeroGradient;\n"}}));
  const std::string flux_pressure = "        type            fixedFluxPressure;\n        value           uniform 0;\n";
  write_case_file(dir, "0/p_rgh",
                  field_file("volScalarField", "p_rgh", "[1 -1 -2 0 0 0 0]", "uniform 0",
                             {{"inlet", flux_pressure},
                              {"outlet", "        type            zeroGradient;\n"},
                              {"atmosphere", "        type            totalPressure;\n        p0              uniform 0;\n"},
                              {"floor", flux_pressure},
                              {"dam", flux_pressure}}));
  if (turbulent(s)) {
    const auto t = turbulence_init(s);
    const auto open = [](double v) {
      return fmt::format("        type            inletOutlet;\n        inletValue      uniform {0};\n"
                         "        value           uniform {0};\n",
                         num(v));
    };
    const auto fixed = [](double v) {
      return fmt::format("        type            fixedValue;\n        value           uniform {};\n", num(v));
    };
    const auto wall = [](const char* type, double v) {
      return fmt::format("        type            {};\n        value           uniform {};\n", type, num(v));
    };
    // k and epsilon: fixed at the inlet, inletOutlet where flow may leave, wall functions.
    const auto transported = [&](const std::string& name, const std::string& dims, double v, const char* wall_type) {
      write_case_file(dir, "0/" + name,
                      field_file("volScalarField", name, dims, "uniform " + num(v),
                                 {{"inlet", fixed(v)},
                                  {"outlet", open(v)},
                                  {"atmosphere", open(v)},
                                  {"floor", wall(wall_type, v)},
                                  {"dam", wall(wall_type, v)}}));
    };
    transported("k", "[0 2 -2 0 0 0 0]", t.k, "kqRWallFunction");
    transported("epsilon", "[0 2 -3 0 0 0 0]", t.epsilon, "epsilonWallFunction");
    const std::string calc = "        type            calculated;\n        value           uniform 0;\n";
    // Smooth walls, or Nikuradse sand of height k_s (Cs 0.5) on the dam and the floor.
    const std::string nut_wall =
        s.flow.wall_roughness > 0
            ? fmt::format(
                  "        type            nutkRoughWallFunction;\n        Ks              uniform {};\n"
                  "        Cs              uniform 0.5;\n        value           uniform 0;\n",
                  num(s.flow.wall_roughness))
            : wall("nutkWallFunction", 0.0);
    write_case_file(
        dir, "0/nut",
        field_file("volScalarField", "nut", "[0 2 -1 0 0 0 0]", "uniform 0",
                   {{"inlet", calc}, {"outlet", calc}, {"atmosphere", calc}, {"floor", nut_wall}, {"dam", nut_wall}}));
  }
}

void write_constant(const FoamScene& s, const fs::path& dir) {
  write_case_file(dir, "constant/g",
                  foam_header("uniformDimensionedVectorField", "g", "constant") +
                      fmt::format("dimensions      [0 1 -2 0 0 0 0];\nvalue           (0 {} 0);\n", num(-s.gravity)));
  write_case_file(dir, "constant/transportProperties",
                  foam_header("dictionary", "transportProperties", "constant") +
                      fmt::format("phases (water air);\n\n"
                                  "water\n{{\n    transportModel  Newtonian;\n    nu              {};\n    rho             {};\n}}\n\n"
                                  "air\n{{\n    transportModel  Newtonian;\n    nu              {};\n    rho             {};\n}}\n\n"
                                  "sigma           {};\n",
                                  num(s.flow.water.viscosity), num(s.flow.water.density), num(s.flow.air.viscosity),
                                  num(s.flow.air.density), num(s.flow.surface_tension)));
  write_case_file(dir, "constant/turbulenceProperties",
                  foam_header("dictionary", "turbulenceProperties", "constant") +
                      (turbulent(s) ? "simulationType  RAS;\n\nRAS\n{\n    RASModel        kEpsilon;\n    turbulence      on;\n"
                                      "    printCoeffs     on;\n}\n"
                                    : "simulationType  laminar;\n"));
}

void write_numerics(const fs::path& dir) {
  write_case_file(dir, "system/fvSchemes",
                  foam_header("dictionary", "fvSchemes", "system") +
                      "ddtSchemes\n{\n    default         Euler;\n}\n\n"
                      "gradSchemes\n{\n    default         Gauss linear;\n}\n\n"
                      "divSchemes\n{\n"
                      "    div(rhoPhi,U)   Gauss linearUpwind grad(U);\n"
                      "    div(phi,alpha)  Gauss vanLeer;\n"
                      "    div(phirb,alpha) Gauss linear;\n"
                      "    div(phi,k)      Gauss upwind;\n"
                      "    div(phi,epsilon) Gauss upwind;\n"
                      "    div(((rho*nuEff)*dev2(T(grad(U))))) Gauss linear;\n}\n\n"
                      "laplacianSchemes\n{\n    default         Gauss linear corrected;\n}\n\n"
                      "interpolationSchemes\n{\n    default         linear;\n}\n\n"
                      "snGradSchemes\n{\n    default         corrected;\n}\n\n"
                      "wallDist\n{\n    method          meshWave;\n}\n");
  write_case_file(dir, "system/fvSolution",
                  foam_header("dictionary", "fvSolution", "system") +
                      "solvers\n{\n"
                      "    \"alpha.water.*\"\n    {\n        nAlphaCorr      2;\n        nAlphaSubCycles 1;\n"
                      "        cAlpha          1;\n        MULESCorr       yes;\n        nLimiterIter    3;\n"
                      "        solver          smoothSolver;\n        smoother        symGaussSeidel;\n"
                      "        tolerance       1e-8;\n        relTol          0;\n    }\n"
                      "    \"pcorr.*\"\n    {\n        solver          PCG;\n        preconditioner  DIC;\n"
                      "        tolerance       1e-5;\n        relTol          0;\n    }\n"
                      "    p_rgh\n    {\n        solver          PCG;\n        preconditioner  DIC;\n"
                      "        tolerance       1e-7;\n        relTol          0.05;\n    }\n"
                      "    p_rghFinal\n    {\n        $p_rgh;\n        relTol          0;\n    }\n"
                      "    \"(U|k|epsilon).*\"\n    {\n        solver          smoothSolver;\n"
                      "        smoother        symGaussSeidel;\n        tolerance       1e-6;\n        relTol          0;\n    }\n"
                      "}\n\n"
                      "PIMPLE\n{\n    momentumPredictor no;\n    nOuterCorrectors 1;\n    nCorrectors     3;\n"
                      "    nNonOrthogonalCorrectors 0;\n}\n\n"
                      "relaxationFactors\n{\n    equations\n    {\n        \".*\" 1;\n    }\n}\n");
}

namespace {

void write_system(const FoamScene& s, const SectionLayout& L, const fs::path& dir) {
  write_case_file(dir, "system/blockMeshDict", block_mesh_dict(L));
  write_numerics(dir);

  // The reservoir (and tailwater) as water at t = 0: cells whose centre lies below the level,
  // upstream of the crest (downstream of it for the tailwater).
  std::string regions = fmt::format(
      "    boxToCell\n    {{\n        box ({} {} -1) ({} {} 1);\n"
      "        fieldValues ( volScalarFieldValue alpha.water 1 );\n    }}\n",
      num(L.x_inlet - 1.0), num(L.floor - 1.0), num(L.dam_nodes.front().x() + s.dam.upstream_slope * s.dam.height),
      num(s.initial_level));
  // The inlet faces under the reservoir level start wet: variableHeightFlowRateInletVelocity
  // spreads the discharge over the wetted part of the inlet and divides by its area.
  regions += fmt::format(
      "    boxToFace\n    {{\n        box ({} {} -1) ({} {} 1);\n"
      "        fieldValues ( volScalarFieldValue alpha.water 1 );\n    }}\n",
      num(L.x_inlet - 0.01 * s.mesh.cell_size), num(L.floor - 1.0), num(L.x_inlet + 0.01 * s.mesh.cell_size),
      num(s.initial_level));
  if (s.tailwater_level)
    regions += fmt::format(
        "    boxToCell\n    {{\n        box ({} {} -1) ({} {} 1);\n"
        "        fieldValues ( volScalarFieldValue alpha.water 1 );\n    }}\n",
        num(L.x_crest_section), num(L.floor - 1.0), num(L.x_outlet + 1.0), num(*s.tailwater_level));
  write_case_file(dir, "system/setFieldsDict",
                  foam_header("dictionary", "setFieldsDict", "system") +
                      "defaultFieldValues ( volScalarFieldValue alpha.water 0 );\n\nregions\n(\n" + regions + ");\n");

  // Face zones at the crest and toe stations: the faces between two columns there (their
  // normals point downstream, see block_mesh_dict.hpp).
  std::string actions;
  const double eps = 0.01 * s.mesh.cell_size;
  for (const auto& [name, x] : {std::pair<std::string, double>{"crest", L.x_crest_section}, {"toe", L.x_toe_section}}) {
    actions += fmt::format(
        "    {{\n        name    {0}Faces;\n        type    faceSet;\n        action  new;\n        source  boxToFace;\n"
        "        sourceInfo\n        {{\n            box ({1} {2} -1) ({3} {4} 1);\n        }}\n    }}\n"
        "    {{\n        name    {0};\n        type    faceZoneSet;\n        action  new;\n        source  setToFaceZone;\n"
        "        sourceInfo\n        {{\n            faceSet {0}Faces;\n        }}\n    }}\n",
        name, num(x - eps), num(L.floor - 1.0), num(x + eps), num(L.top + 1.0));
  }
  write_case_file(dir, "system/topoSetDict",
                  foam_header("dictionary", "topoSetDict", "system") + "actions\n(\n" + actions + ");\n");

  write_case_file(dir, "system/decomposeParDict",
                  foam_header("dictionary", "decomposeParDict", "system") +
                      fmt::format("numberOfSubdomains {};\n\nmethod          {};\n\n"
                                  "coeffs\n{{\n    n               ({} 1 1);\n    order           xyz;\n}}\n",
                                  s.run.ranks, s.run.decomposition, s.run.ranks));
}

// Discharge through one section per time step, water (alphaPhi0.water) and mixture (phi).
std::string flux_function(const std::string& name, bool zone) {
  return fmt::format(
      "    {0}Discharge\n    {{\n        type            surfaceFieldValue;\n"
      "        libs            (\"libfieldFunctionObjects.so\");\n        writeControl    timeStep;\n"
      "        writeInterval   1;\n        log             false;\n        writeFields     false;\n"
      "        regionType      {1};\n        name            {0};\n        operation       sum;\n"
      "        fields          (alphaPhi0.water phi);\n    }}\n",
      name, zone ? "faceZone" : "patch");
}

}  // namespace

std::string inlet_flow_rate(const FoamScene& s, const SectionLayout& L) {
  // Slab discharge = q(t) * thickness, q = Q / crest_length.
  const double per_q = L.thickness / s.dam.crest_length;
  if (s.inflow.kind() == Hydrograph::Kind::constant) return "constant " + num(s.inflow(0.0) * per_q);
  std::vector<double> times = s.inflow.breakpoints();
  if (times.empty()) {  // a smooth law (sine): sampled finely enough for linear interpolation
    const int n = 400;
    for (int i = 0; i <= n; ++i) times.push_back(s.time.end * i / n);
  }
  std::string out = "table\n        (\n";
  for (double t : times) out += fmt::format("            ({} {})\n", num(t), num(s.inflow(t) * per_q));
  out += "        )";
  return out;
}

void write_control_dict(const FoamScene& s, const fs::path& dir, double end_time) {
  const double dt0 = s.time.fixed_dt ? *s.time.fixed_dt : std::min(s.time.max_dt, 1e-3);
  std::string functions = "functions\n{\n";
  functions += flux_function("inlet", false) + flux_function("crest", true) + flux_function("toe", true) +
               flux_function("outlet", false);
  functions += fmt::format(
      "    wallShearStress\n    {{\n        type            wallShearStress;\n"
      "        libs            (\"libfieldFunctionObjects.so\");\n        patches         ({});\n"
      "        writeControl    writeTime;\n        log             false;\n    }}\n",
      kDamPatch);
  functions += "}\n";
  write_case_file(dir, "system/controlDict",
                  foam_header("dictionary", "controlDict", "system") +
                      fmt::format("application     interFoam;\nstartFrom       latestTime;\nstartTime       0;\n"
                                  "stopAt          endTime;\nendTime         {};\ndeltaT          {};\n"
                                  "writeControl    adjustableRunTime;\nwriteInterval   {};\npurgeWrite      0;\n"
                                  "writeFormat     ascii;\nwritePrecision  12;\nwriteCompression off;\n"
                                  "timeFormat      general;\ntimePrecision   12;\nrunTimeModifiable no;\n"
                                  "adjustTimeStep  {};\nmaxCo           {};\nmaxAlphaCo      {};\nmaxDeltaT       {};\n\n",
                                  num(end_time), num(dt0), num(s.time.write_interval),
                                  s.time.fixed_dt ? "no" : "yes", num(s.time.max_courant),
                                  num(s.time.max_alpha_courant), num(s.time.max_dt)) +
                      functions);
}

void write_case_setup(const FoamScene& scene, const SectionLayout& layout, const fs::path& case_dir,
                      double end_time) {
  fs::create_directories(case_dir);
  write_constant(scene, case_dir);
  write_system(scene, layout, case_dir);
  write_control_dict(scene, case_dir, end_time);
}

}  // namespace suite::foam_erosion

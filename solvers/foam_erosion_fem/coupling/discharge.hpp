#pragma once
// Discharge through the sections the case measures (the surfaceFieldValue function objects
// inletDischarge, crestDischarge, toeDischarge, outletDischarge of case/case_writer.hpp).
//
// Each run of interFoam writes postProcessing/<name>Discharge/<start time>/surfaceFieldValue.dat
// with one row per time step: time, sum(alphaPhi0.water), sum(phi). The series of a section is
// those files in start-time order, a later file's rows replacing the earlier rows from its first
// time on (a run restarted from an earlier time directory repeats some times).
#include <filesystem>
#include <string>
#include <vector>

namespace suite::foam_erosion {

struct DischargeSeries {
  std::vector<double> time;     // s
  std::vector<double> water;    // m^3/s through the one-cell slab, water only (alphaPhi0.water)
  std::vector<double> mixture;  // m^3/s through the slab, water and air (phi)
};

// FoamReadError names the file and line if a row is malformed or no file is there.
DischargeSeries read_discharge(const std::filesystem::path& case_dir, const std::string& section);

// discharge.csv: time and the water discharge Q (m^3/s over the whole crest length, `scale` =
// crest_length / slab thickness) through each section, inflow counted positive at the inlet,
// on the time steps all sections share.
void write_discharge_csv(const std::filesystem::path& file, const std::vector<std::string>& sections,
                         const std::vector<DischargeSeries>& series, double scale);

// Mean of `values` over the samples with time in (t0, t1], weighted by the time step.
double time_mean(const std::vector<double>& time, const std::vector<double>& values, double t0, double t1);

}  // namespace suite::foam_erosion

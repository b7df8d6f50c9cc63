#pragma once
// XDMF (version 3) sidecar so ParaView opens the HDF5 output steps as one time series.
//
// The .xmf file holds one temporal collection; each step is a spatial collection of grids
// (particles, active grid nodes...) whose arrays live in that step's HDF5 file. Only rank 0
// writes; the file is rewritten atomically after each step, so a crash never leaves half a
// file, and `resume_at` drops the steps after a restart time. Not collective.
#include <filesystem>
#include <string>
#include <vector>

namespace suite::io {

struct XdmfArray {
  std::string name;                   // attribute name shown in ParaView
  std::string dataset;                // path inside the HDF5 file, e.g. "/particles/velocity"
  long long rows = 0;                 // first dimension
  int cols = 1;                       // 1: scalar, 3: vector, otherwise a matrix
  std::string number_type = "Float";  // Float, Int, UInt, Char, UChar
  int precision = 8;                  // bytes
};

enum class XdmfTopology { polyvertex, polyline, triangle, quadrilateral, tetrahedron, hexahedron };

struct XdmfGrid {
  std::string name;     // e.g. "particles", "grid_nodes"
  std::string h5_file;  // HDF5 file name, relative to the .xmf's folder
  XdmfTopology topology = XdmfTopology::polyvertex;
  XdmfArray geometry;      // rows x 2 ("XY") or rows x 3 ("XYZ") coordinates
  XdmfArray connectivity;  // cells x nodes-per-cell (not used for polyvertex)
  std::vector<XdmfArray> node_attributes;
  std::vector<XdmfArray> cell_attributes;
};

class XdmfSeries {
 public:
  explicit XdmfSeries(std::filesystem::path xmf_path);
  // Keeps the steps of an existing file with time <= t (restart); none if the file is absent.
  void resume_at(double t);
  // Appends a step and rewrites the file.
  void add_step(double time, const std::vector<XdmfGrid>& grids);
  std::size_t steps() const { return blocks_.size(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  void write() const;
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> blocks_;  // (time, XML of the step)
};

}  // namespace suite::io

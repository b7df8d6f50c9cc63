#include "core/io/xdmf.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::io {

namespace {

constexpr std::string_view kBegin = "<!-- step begin time=";
constexpr std::string_view kEnd = "<!-- step end -->";

const char* topology_name(XdmfTopology t) {
  switch (t) {
    case XdmfTopology::polyvertex:
      return "Polyvertex";
    case XdmfTopology::polyline:
      return "Polyline";
    case XdmfTopology::triangle:
      return "Triangle";
    case XdmfTopology::quadrilateral:
      return "Quadrilateral";
    case XdmfTopology::tetrahedron:
      return "Tetrahedron";
    case XdmfTopology::hexahedron:
      return "Hexahedron";
  }
  return "Polyvertex";
}

std::string data_item(const XdmfArray& a, const std::string& h5_file) {
  const std::string dims = a.cols == 1 ? fmt::format("{}", a.rows) : fmt::format("{} {}", a.rows, a.cols);
  return fmt::format(R"(<DataItem Dimensions="{}" NumberType="{}" Precision="{}" Format="HDF">{}:{}</DataItem>)", dims,
                     a.number_type, a.precision, h5_file, a.dataset);
}

std::string attribute(const XdmfArray& a, const std::string& h5_file, const char* center) {
  const char* type = a.cols == 1 ? "Scalar" : (a.cols == 3 ? "Vector" : "Matrix");
  return fmt::format(R"(        <Attribute Name="{}" AttributeType="{}" Center="{}">
          {}
        </Attribute>
)",
                     a.name, type, center, data_item(a, h5_file));
}

std::string grid_xml(const XdmfGrid& g) {
  if (g.geometry.cols != 2 && g.geometry.cols != 3)
    throw LibraryError(fmt::format("XDMF grid '{}': geometry needs 2 or 3 columns, not {}", g.name, g.geometry.cols));
  std::string s = fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n", g.name);
  if (g.topology == XdmfTopology::polyvertex) {
    s += fmt::format(R"(        <Topology TopologyType="Polyvertex" NumberOfElements="{}" NodesPerElement="1"/>
)",
                     g.geometry.rows);
  } else {
    s += fmt::format(R"(        <Topology TopologyType="{}" NumberOfElements="{}" NodesPerElement="{}">
          {}
        </Topology>
)",
                     topology_name(g.topology), g.connectivity.rows, g.connectivity.cols,
                     data_item(g.connectivity, g.h5_file));
  }
  s += fmt::format(R"(        <Geometry GeometryType="{}">
          {}
        </Geometry>
)",
                   g.geometry.cols == 2 ? "XY" : "XYZ", data_item(g.geometry, g.h5_file));
  for (const auto& a : g.node_attributes) s += attribute(a, g.h5_file, "Node");
  for (const auto& a : g.cell_attributes) s += attribute(a, g.h5_file, "Cell");
  s += "      </Grid>\n";
  return s;
}

}  // namespace

XdmfSeries::XdmfSeries(std::filesystem::path xmf_path) : path_(std::move(xmf_path)) {}

void XdmfSeries::resume_at(double t) {
  blocks_.clear();
  std::ifstream in(path_);
  if (!in) return;
  std::string line, block;
  double time = 0;
  bool inside = false;
  while (std::getline(in, line)) {
    const auto b = line.find(kBegin);
    if (b != std::string::npos) {
      inside = true;
      block.clear();
      time = std::stod(line.substr(b + kBegin.size()));
    }
    if (inside) block += line + "\n";
    if (inside && line.find(kEnd) != std::string::npos) {
      inside = false;
      if (time <= t) blocks_.emplace_back(time, block);
    }
  }
}

void XdmfSeries::add_step(double time, const std::vector<XdmfGrid>& grids) {
  std::string s = fmt::format("    {}{:.17g} -->\n", kBegin, time);
  s += fmt::format("    <Grid Name=\"step_{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n", blocks_.size());
  s += fmt::format("      <Time Value=\"{:.17g}\"/>\n", time);
  for (const auto& g : grids) s += grid_xml(g);
  s += fmt::format("    </Grid>\n    {}\n", kEnd);
  blocks_.emplace_back(time, std::move(s));
  write();
}

void XdmfSeries::write() const {
  std::string s = R"(<?xml version="1.0" ?>
<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>
<Xdmf Version="3.0">
  <Domain>
  <Grid Name="time_series" GridType="Collection" CollectionType="Temporal">
)";
  for (const auto& [t, block] : blocks_) s += block;
  s += "  </Grid>\n  </Domain>\n</Xdmf>\n";
  write_file_atomic(path_, s);
}

}  // namespace suite::io

#include "run_file/xdmf_sidecar.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace tongue::run_file {

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// 17 significant digits: the text reads back as the same double.
std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

std::string xdmf_sidecar_path(const std::string& h5_path) {
  return std::filesystem::path(h5_path).replace_extension(".xmf").string();
}

std::string xdmf_text(const XdmfRun& run) {
  const std::string h5 = xml_escape(run.h5_file);
  const std::string n = std::to_string(run.num_nodes);
  const std::string e = std::to_string(run.num_elements);
  const std::string t = std::to_string(run.times.size());
  const std::string topology = "      <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" +
                               e +
                               "\" NodesPerElement=\"8\">\n"
                               "        <DataItem Dimensions=\"" +
                               e +
                               " 8\" NumberType=\"Int\" Precision=\"4\" "
                               "Format=\"HDF\">" +
                               h5 +
                               ":/elements</DataItem>\n"
                               "      </Topology>\n";
  std::string s =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<!-- Written by the tongue simulation server next to " +
      h5 +
      "; open it in ParaView with\n"
      "     the \"XDMF Reader\" (Xdmf2). Node positions in m. -->\n"
      "<Xdmf Version=\"2.0\">\n"
      "  <Domain>\n";
  if (run.times.empty()) {
    s += "    <Grid Name=\"rest\" GridType=\"Uniform\">\n" + topology +
         "      <Geometry GeometryType=\"XYZ\">\n"
         "        <DataItem Dimensions=\"" +
         n +
         " 3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">" +
         h5 +
         ":/rest_positions</DataItem>\n"
         "      </Geometry>\n"
         "    </Grid>\n";
  } else {
    s += "    <Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t k = 0; k < run.times.size(); ++k) {
      s += "    <Grid Name=\"frame " + std::to_string(k) +
           "\" GridType=\"Uniform\">\n"
           "      <Time Value=\"" +
           exact(run.times[k]) + "\" />\n" + topology +
           "      <Geometry GeometryType=\"XYZ\">\n"
           "        <DataItem ItemType=\"HyperSlab\" Dimensions=\"1 " +
           n +
           " 3\" "
           "Type=\"HyperSlab\">\n"
           "          <DataItem Dimensions=\"3 3\" Format=\"XML\">" +
           std::to_string(k) + " 0 0 1 1 1 1 " + n +
           " 3</DataItem>\n"
           "          <DataItem Dimensions=\"" +
           t + " " + n +
           " 3\" NumberType=\"Float\" "
           "Precision=\"8\" Format=\"HDF\">" +
           h5 +
           ":/positions</DataItem>\n"
           "        </DataItem>\n"
           "      </Geometry>\n"
           "    </Grid>\n";
    }
    s += "    </Grid>\n";
  }
  s += "  </Domain>\n</Xdmf>\n";
  return s;
}

void write_xdmf_sidecar(const std::string& xmf_path, const XdmfRun& run) {
  const std::string tmp = xmf_path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << xdmf_text(run);
    out.close();
    if (!out) throw std::runtime_error(xmf_path + ": cannot write the XDMF sidecar");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xmf_path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(xmf_path + ": cannot write the XDMF sidecar: " + ec.message());
  }
}

}  // namespace tongue::run_file

#pragma once
// Results for ParaView and for scripts: an HDF5 file with one group per output step and an XDMF
// index (temporal collections "bodies" and "joints" as polyvertex grids with node frames (axes and
// quaternion), "beams" as line segments in the deformed configuration with section forces and
// strains as cell data, and "shells" as triangles and quadrilaterals (one XDMF Mixed topology) in
// the deformed configuration with stress resultants and von Mises stresses as cell data;
// Precision="8" doubles),
// plus the sensors as CSV (header row, first column t, 17 significant digits).
//
// With the replicated state of the core engine, rank 0 writes everything; the parallel issue
// switches the HDF5 side to collective MPI-IO writes of the same layout.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"

namespace alphaflex {

class ResultsWriter {
 public:
  /// Creates OUTDIR/NAME.h5 (if `hdf5`), OUTDIR/NAME.xdmf and OUTDIR/NAME.csv on rank 0.
  ResultsWriter(const Model& model, const std::string& outdir, const std::string& name, bool hdf5, int rank);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// One CSV row: time and the sensor values in scene order.
  void write_sensors(double t, const std::vector<double>& values);
  /// Full state to HDF5 (one group) and a rewritten XDMF index.
  void write_fields(const MechanicalState& s);
  /// Flush and write the XDMF index (called at the end, also after a failure).
  void finish();

  std::string h5_path() const { return h5_path_; }
  std::string xdmf_path() const { return xdmf_path_; }
  std::string csv_path() const { return csv_path_; }
  int fields_written() const { return static_cast<int>(times_.size()); }

 private:
  void write_xdmf() const;

  const Model& model_;
  bool active_, hdf5_;
  std::string h5_path_, xdmf_path_, csv_path_, h5_name_;
  long long file_ = -1;  // hid_t
  std::FILE* csv_ = nullptr;
  std::vector<double> times_;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  std::vector<std::string> groups_;
  std::vector<int> beams_;                 ///< elements drawn as beam segments
  std::vector<std::string> beam_fields_;   ///< their result fields (cell data)
  std::vector<int> shells_;                ///< elements drawn as shell triangles and quadrilaterals
  std::vector<std::string> shell_fields_;  ///< their result fields (cell data)
  size_t shell_topology_size_ = 0;         ///< length of /topology/shell_connectivity (Mixed)
};

}  // namespace alphaflex

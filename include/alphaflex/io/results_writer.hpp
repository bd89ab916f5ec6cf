#pragma once
// Results for ParaView and for scripts: an HDF5 file with one group per output step and an XDMF
// index (temporal collections "bodies" and "joints" as polyvertex grids with node frames (axes and
// quaternion), "beams" as line segments in the deformed configuration with section forces and
// strains as cell data, and "shells" as triangles and quadrilaterals (one XDMF Mixed topology) in
// the deformed configuration with stress resultants and von Mises stresses as cell data;
// Precision="8" doubles),
// plus the sensors as CSV (header row, first column t, 17 significant digits).
//
// In parallel every rank writes the rows it owns (its nodes, elements and joints, at their places
// in model order) with collective MPI-IO writes of parallel HDF5, so the file has the same layout
// and order whatever the number of ranks; rank 0 writes the CSV and the XDMF index (small text).
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

class ResultsWriter {
 public:
  /// Creates OUTDIR/NAME.csv (rank 0) and OUTDIR/NAME.h5 (if `hdf5`; every rank, MPI-IO).
  /// Collective; throws InputError on every rank if any part failed.
  ResultsWriter(const Subdomain& subdomain, const std::string& outdir, const std::string& name, bool hdf5);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// One CSV row (rank 0): time and the sensor values in scene order (the same on every rank).
  void write_sensors(double t, const std::vector<double>& values);
  /// This rank's part of the state `s` (its subdomain's local state) to HDF5, one group per call.
  /// Collective.
  void write_fields(const MechanicalState& s);
  /// Flush and write the XDMF index (called at the end, also after a failure). Collective.
  void finish();

  std::string h5_path() const { return h5_path_; }
  std::string xdmf_path() const { return xdmf_path_; }
  std::string csv_path() const { return csv_path_; }
  int fields_written() const { return static_cast<int>(times_.size()); }

 private:
  /// Rows of a dataset that this rank writes: intervals [start, start + count) of its first
  /// dimension (sorted, disjoint), out of `total` rows.
  struct Rows {
    std::vector<unsigned long long> start, count;
    unsigned long long total = 0, mine = 0;
    void add(unsigned long long first, unsigned long long n);
  };
  void write_xdmf() const;
  /// Writes `rows` × `cols` doubles (this rank's rows, in increasing order) into a new dataset of
  /// `total` × `cols` rows of group `loc`. Collective.
  void write_rows(long long loc, const char* name, const Rows& rows, int cols, const double* data);
  void write_int_rows(long long loc, const char* name, const Rows& rows, const int* data);

  const Subdomain& sub_;
  const Model& model_;   ///< the local model (this rank's subdomain)
  const Model& global_;  ///< the whole model: names, counts and layouts
  bool root_, hdf5_;
  std::string h5_path_, xdmf_path_, csv_path_, h5_name_;
  long long file_ = -1, transfer_ = -1;  // hid_t of the file and of the (collective) transfer list
  std::FILE* csv_ = nullptr;
  std::vector<double> times_;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  std::vector<std::string> groups_;
  std::vector<int> beams_;                 ///< global elements drawn as beam segments
  std::vector<std::string> beam_fields_;   ///< their result fields (cell data)
  std::vector<int> shells_;                ///< global elements drawn as shell triangles and quadrilaterals
  std::vector<std::string> shell_fields_;  ///< their result fields (cell data)
  size_t shell_topology_size_ = 0;         ///< length of /topology/shell_connectivity (Mixed)
  // This rank's rows: owned nodes, its joints, its beams and shells, its coordinates (q), node
  // unknowns (v, q̈) and multipliers, and its part of the shell connectivity.
  Rows node_rows_, joint_rows_, beam_rows_, shell_rows_, conf_rows_, dof_rows_, mult_rows_, shell_conn_rows_;
  std::vector<int> local_beams_, local_shells_;  ///< local element indices, in row order
};

}  // namespace alphaflex

// Evaluates a scene's probes (docs/scenes.md, [[output.probe]]) at a state and writes them as
// one CSV row per output time. Rows are flushed as written, so a run that fails part-way keeps
// every row before the failure.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/contact_output.hpp"

namespace ancf {

class ProbeRecorder {
 public:
  /// Ownership: keeps references to `model` and `probes`, which must outlive the recorder.
  ProbeRecorder(const Model& model, const std::vector<Probe>& probes);

  /// "t" followed by every probe's columns (label.suffix).
  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  /// Values of columns() at `state` (t first). Contact probes also update the first-contact
  /// times of contact_monitor().
  [[nodiscard]] const std::vector<double>& evaluate(const SystemState& state, Workspace& ws);
  [[nodiscard]] const ContactMonitor& contact_monitor() const { return monitor_; }
  /// The values of the last evaluate() (empty before the first).
  [[nodiscard]] const std::vector<double>& last_row() const { return row_; }

 private:
  const Model& model_;
  const std::vector<Probe>& probes_;
  std::vector<std::string> columns_;
  std::vector<double> row_;
  ContactMonitor monitor_;
};

/// probes.csv: a header line of column names, then one line per row, flushed per row. Values are
/// written at full precision: the shortest decimal that reads back (strtod) to the same double,
/// at most 17 significant digits; nan and inf as "nan", "inf".
class CsvWriter {
 public:
  /// Throws ModelError if the file cannot be created.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  void write(const std::vector<double>& row);
  [[nodiscard]] long rows() const { return rows_; }

 private:
  std::ofstream out_;
  long rows_ = 0;
};

}  // namespace ancf

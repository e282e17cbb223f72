#include "sim/sweep_csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace polysim::sim {
namespace {

std::string joined(const std::vector<std::string>& fields) {
  std::string line;
  for (const std::string& f : fields) line += (line.empty() ? "" : ",") + f;
  return line;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields(1);
  for (char c : line) {
    if (c == ',')
      fields.emplace_back();
    else
      fields.back() += c;
  }
  return fields;
}

// Reads one line's fields by column, each error naming where it is.
class RowReader {
 public:
  RowReader(const std::vector<std::string>& fields, const std::string& where) : fields_(fields), where_(where) {}

  const std::string& text(size_t column) const {
    if (fields_[column].empty()) fail(column, "is empty");
    return fields_[column];
  }
  double number(size_t column) const {
    const std::string& field = text(column);
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size() || errno == ERANGE || !std::isfinite(value))
      fail(column, "is not a finite number: \"" + field + "\"");
    return value;
  }

 private:
  [[noreturn]] void fail(size_t column, const std::string& what) const {
    throw std::runtime_error(where_ + ": column " + sweepCsvColumns()[column] + " " + what);
  }
  const std::vector<std::string>& fields_;
  const std::string& where_;
};

}  // namespace

const std::vector<std::string>& sweepCsvColumns() {
  static const std::vector<std::string> columns = {
      "scene", "engine",   "solver",   "parameter_name", "parameter",       "dt",    "wall_s",          "cost_s_per_s",
      "metric", "measured", "analytic", "error",          "solver_warnings", "cpu_s", "cpu_cost_s_per_s"};
  return columns;
}

void writeSweepCsv(const std::vector<SweepRow>& rows, std::ostream& out) {
  out << joined(sweepCsvColumns()) << "\n";
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (const SweepRow& r : rows)
    out << r.scene << "," << r.setting.engine << "," << r.setting.solver << "," << r.setting.parameterName << ","
        << r.setting.parameter << "," << r.setting.dt << "," << r.wallTime << "," << r.cost << "," << r.metric << ","
        << r.measured << "," << r.analytic << "," << r.error << "," << r.solverWarnings << "," << r.cpuTime << ","
        << r.cpuCost << "\n";
}

std::vector<SweepRow> readSweepCsv(std::istream& in, const std::string& source) {
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(source + ": empty, not a sweep CSV");
  if (line != joined(sweepCsvColumns()))
    throw std::runtime_error(source + ": line 1 is not the sweep CSV's header");
  std::vector<SweepRow> rows;
  for (long number = 2; std::getline(in, line); ++number) {
    const std::string where = source + ": line " + std::to_string(number);
    if (in.eof()) throw std::runtime_error(where + " has no newline: the file was cut short");
    const std::vector<std::string> fields = split(line);
    if (fields.size() != sweepCsvColumns().size())
      throw std::runtime_error(where + " has " + std::to_string(fields.size()) + " fields, not " +
                               std::to_string(sweepCsvColumns().size()));
    const RowReader f(fields, where);
    SweepRow r;
    r.scene = f.text(0);
    r.setting = {f.text(1), f.text(2), f.text(3), f.number(4), f.number(5)};
    r.wallTime = f.number(6);
    r.cost = f.number(7);
    r.metric = f.text(8);
    r.measured = f.number(9);
    r.analytic = f.number(10);
    r.error = f.number(11);
    r.solverWarnings = std::lround(f.number(12));
    r.cpuTime = f.number(13);
    r.cpuCost = f.number(14);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace polysim::sim

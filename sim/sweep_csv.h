#pragma once
// The sweep's CSV, written and read back: the one format that the serial sweep, each
// planned run and the merge produce, and that plot_sweep.py draws.

#include <iosfwd>
#include <string>
#include <vector>

#include "sim/sweep.h"

namespace polysim::sim {

/// The header line's columns, in order: scene, engine, solver, parameter_name, parameter,
/// dt, wall_s, cost_s_per_s, metric, measured, analytic, error, solver_warnings, cpu_s,
/// cpu_cost_s_per_s.
const std::vector<std::string>& sweepCsvColumns();

/// The header, then a row per figure. Numbers at full precision, so that reading them
/// back gives the same doubles.
void writeSweepCsv(const std::vector<SweepRow>& rows, std::ostream& out);

/// Reads what writeSweepCsv wrote. Throws std::runtime_error naming `source`, the line and
/// the column on anything else: another header, a missing or extra field, a number that
/// does not parse or is not finite, a last line without its newline (a file cut short).
std::vector<SweepRow> readSweepCsv(std::istream& in, const std::string& source);

}  // namespace polysim::sim

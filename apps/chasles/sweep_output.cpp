#include "sweep_output.h"

#include <cstdio>

#include <fmt/format.h>

#include "chasles/report/json_report.h"
#include "chasles/report/solve_json.h"
#include "scene_args.h"

namespace chasles::cli {

void AddSweepOptions(CLI::App& cmd, std::vector<std::string>& sweep,
                     std::vector<std::string>& quantity, int& jobs, std::int64_t& max_runs,
                     const std::string& what) {
  cmd.add_option("--sweep", sweep,
                 "Repeat over a parameter range: NAME=START:STOP:COUNT (START and STOP are "
                 "expressions with units, e.g. 'L=0.5 m:2 m:4'); repeat it for a grid of every "
                 "combination (the last varying fastest). Prints a table, CSV or --format json; "
                 "under mpirun -np N the points are split over the processes (docs/sweeps.md)")
      ->allow_extra_args(false);
  cmd.add_option("--quantity", quantity, "With --sweep, a column of the table: " + what)
      ->allow_extra_args(false)
      ->delimiter('\0');  // keep "event(a, 2)" whole
  cmd.add_option("--jobs", jobs,
                 "With --sweep, the runs done at once (default: the number of cores; fewer when "
                 "the system cannot start more threads); the table is the same for any number")
      ->check(WholeNumber(kMaxJobs));
  cmd.add_option("--max-runs", max_runs,
                 fmt::format("Most points of a sweep (default {}); a larger grid is refused",
                             kDefaultMaxRuns))
      ->check(WholeNumber(kMaxWholeNumber));
}

std::vector<SweepSpec> ParseSweeps(const std::vector<std::string>& texts) {
  std::vector<SweepSpec> specs;
  for (const std::string& t : texts) specs.push_back(ParseSweep(t, "command line", "--sweep"));
  return specs;
}

int AddSweepTable(OutputSet& out, const SweepTable& table, const std::string& format,
                  CsvPrecision precision, const std::string& target) {
  const std::string text =
      format == "json" ? DumpJson(SweepJson(table), "the sweep table") : SweepCsv(table, precision);
  int failed = 0;
  for (size_t r = 0; r < table.errors.size(); ++r) {
    if (table.errors[r].empty()) continue;
    ++failed;
    std::string where;
    for (size_t p = 0; p < table.parameters.size(); ++p) {
      where += fmt::format("{}{} = {:.12g}", p ? ", " : "", table.parameters[p], table.rows[r][p]);
    }
    std::fprintf(stderr, "warning: %s: %s\n", where.c_str(), table.errors[r].c_str());
  }
  out.Add(target, text);
  return failed;
}

}  // namespace chasles::cli

// What contact costs: a cloth of about 10K vertices dropped on a sphere, 50 steps. Splits each
// step's time into broad phase, CCD, barrier assembly, friction assembly, factorization and
// the rest, and measures in the same run how much contact adds over the same scene with contact
// disabled while the cloth is still falling (before it touches). Prints tables, writes CSV.
//
// usage: bench_contact_breakdown [csv_path] [grid_n] [steps]
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "bench_main.hpp"
#include "cloth_over_sphere.hpp"
#include "contact/contact_potential.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

/// Seconds of one step by phase.
struct Split {
  double total = 0, broad_phase = 0, ccd = 0, barrier = 0, friction = 0, analysis = 0,
         factorization = 0;
  int iterations = 0, symbolic_analyses = 0;
  long active_pairs = 0, candidates = 0;
  double other() const {
    return total - broad_phase - ccd - barrier - friction - analysis - factorization;
  }
  void add(const Split& s) {
    total += s.total, broad_phase += s.broad_phase, ccd += s.ccd, barrier += s.barrier;
    friction += s.friction, analysis += s.analysis, factorization += s.factorization;
    iterations += s.iterations;
    symbolic_analyses += s.symbolic_analyses;
    active_pairs += s.active_pairs, candidates += s.candidates;
  }
};

Split split_of(const StepRecord& r) {
  Split s;
  s.total = r.seconds;
  s.analysis = r.newton.timings.analysis;
  s.factorization = r.newton.timings.factorization;
  s.iterations = r.newton.iterations;
  s.symbolic_analyses = r.newton.symbolic_analyses;
  if (r.contact) {
    s.broad_phase = r.contact->broad_phase_seconds;
    s.ccd = r.contact->ccd_seconds;
    s.barrier = r.contact->assembly_seconds;
    s.active_pairs = r.contact->active_pairs;
    s.candidates = r.contact->candidate_pairs;
  }
  for (const TermStats& t : r.terms)
    if (t.name == "friction") s.friction = t.seconds;
  return s;
}

void print_row(std::FILE* out, const char* label, const Split& s) {
  std::fprintf(out, "%-22s %9.3f %7d %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f\n", label, s.total,
               s.iterations, s.broad_phase, s.ccd, s.barrier, s.friction, s.analysis,
               s.factorization, s.other());
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "contact_breakdown.csv";
  const int n = argc > 2 ? std::atoi(argv[2]) : 100;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 50;

  LevelSimulation with_contact(bench::cloth_over_sphere(n, steps, true));
  std::printf("cloth %d vertices + sphere %d vertices, %d steps of h = 0.01 s\n",
              with_contact.model().rest.num_vertices(),
              with_contact.contact()->mesh().num_obstacle_vertices, steps);
  std::vector<Split> per_step;
  int first_touch = -1;
  for (int s = 0; s < steps; ++s) {
    const StepRecord r = with_contact.step();
    per_step.push_back(split_of(r));
    if (first_touch < 0 && r.contact->active_pairs > 0) first_touch = s;
    std::fprintf(stderr, "\rstep %d/%d (%.1f s, %d Newton iterations, %ld active pairs)", s + 1,
                 steps, r.seconds, r.newton.iterations, static_cast<long>(r.contact->active_pairs));
  }
  std::fprintf(stderr, "\n");
  if (first_touch < 0) first_touch = steps;

  // The same scene without contact, for the steps before the cloth touches (then the two
  // runs are identical motions, so the time difference is what contact checking costs).
  LevelSimulation without_contact(bench::cloth_over_sphere(n, steps, false));
  Split free_fall, falling_with_contact, touching, all;
  for (int s = 0; s < first_touch; ++s) {
    free_fall.add(split_of(without_contact.step()));
    falling_with_contact.add(per_step[s]);
  }
  for (int s = first_touch; s < steps; ++s) touching.add(per_step[s]);
  for (const Split& s : per_step) all.add(s);

  std::printf("\n%-22s %9s %7s %9s %9s %9s %9s %9s %9s %9s\n", "phase (seconds)", "total", "newton",
              "broad", "ccd", "barrier", "friction", "analysis", "factor", "other");
  print_row(stdout, "falling, no contact", free_fall);
  print_row(stdout, "falling, contact on", falling_with_contact);
  print_row(stdout, "touching", touching);
  print_row(stdout, "all steps", all);
  const double overhead = free_fall.total > 0 ? falling_with_contact.total / free_fall.total : 0;
  const double contact_share = (all.broad_phase + all.ccd + all.barrier + all.friction) / all.total;
  std::printf("\nfirst contact at step %d; while falling, contact on / off = %.3f\n",
              first_touch + 1, overhead);
  std::printf(
      "over all steps: contact work (broad + ccd + barrier + friction) = %.1f%% of the "
      "time, factorization = %.1f%%\n",
      100.0 * contact_share, 100.0 * all.factorization / all.total);
  const double touching_contact =
      touching.broad_phase + touching.ccd + touching.barrier + touching.friction;
  std::printf(
      "while touching: contact work / factorization = %.2f; %d symbolic analyses in %d steps "
      "(%d Newton iterations)\n",
      touching.factorization > 0 ? touching_contact / touching.factorization : 0.0,
      touching.symbolic_analyses, steps - first_touch, touching.iterations);

  std::ofstream csv = bench::open_csv(csv_path);
  csv << "step,seconds,newton_iterations,broad_phase,ccd,barrier,friction,analysis,factorization,"
         "other,candidate_pairs,active_pairs,symbolic_analyses\n";
  for (std::size_t s = 0; s < per_step.size(); ++s) {
    const Split& p = per_step[s];
    csv << s + 1 << ',' << p.total << ',' << p.iterations << ',' << p.broad_phase << ',' << p.ccd
        << ',' << p.barrier << ',' << p.friction << ',' << p.analysis << ',' << p.factorization
        << ',' << p.other() << ',' << p.candidates << ',' << p.active_pairs << ','
        << p.symbolic_analyses << '\n';
  }
  csv << "# falling_steps=" << first_touch << " contact_on_over_off_while_falling=" << overhead
      << '\n';
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_contact_breakdown [csv_path] [grid_n] [steps]",
                             run);
}

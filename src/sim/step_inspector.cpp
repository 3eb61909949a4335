#include "sim/step_inspector.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "integrate/schemes.hpp"
#include "sim/stage_trace.hpp"

namespace gs {

void StepInspector::set_verlet_correction(Simulation& sim, VerletCorrection c) {
  if (auto* vv = dynamic_cast<VelocityVerlet*>(sim.integ_.get())) vv->set_correction(c);
}

namespace {

// the stage's name, and the stage that stood for it where that differs
std::string inspected_stage(const StageTrace::Record& a, const StageTrace::Record& b) {
  std::string s(stage_name(a.as));
  if (a.ran != a.as || b.ran != b.as)
    s += " (" + std::string(stage_name(a.ran)) + " vs " + std::string(stage_name(b.ran)) + ")";
  return s;
}

// the records of a and b that describe the same stage of the same step compared and dropped;
// the first difference among them, in step order
std::string compare_matched(StageTrace& ta, StageTrace& tb, std::int64_t now) {
  auto& ra = ta.records();
  auto& rb = tb.records();
  std::string first;
  std::pair<std::int64_t, Stage> first_at{0, Stage::Health};
  std::vector<bool> used_a(ra.size(), false), used_b(rb.size(), false);
  for (std::size_t i = 0; i < ra.size(); ++i) {
    for (std::size_t j = 0; j < rb.size(); ++j) {
      if (used_b[j] || ra[i].step != rb[j].step || ra[i].as != rb[j].as) continue;
      used_a[i] = used_b[j] = true;
      const std::string d = first_difference(ra[i], rb[j]);
      const std::pair<std::int64_t, Stage> at{ra[i].step, ra[i].as};
      if (!d.empty() && (first.empty() || at < first_at)) {
        first_at = at;
        first = "step " + std::to_string(at.first) + ", stage " + inspected_stage(ra[i], rb[j]) +
                ", " + d;
      }
      break;
    }
  }
  // what was matched, and what can no longer be (a record of the other's earlier steps)
  auto drop = [now](std::vector<StageTrace::Record>& r, const std::vector<bool>& used) {
    std::size_t out = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
      if (!used[k] && r[k].step >= now) r[out++] = std::move(r[k]);
    r.resize(out);
  };
  drop(ra, used_a);
  drop(rb, used_b);
  return first;
}

}  // namespace

std::string StepInspector::first_difference(Simulation& a, Simulation& b, std::int64_t steps) {
  StageTrace ta, tb;
  struct Attached {  // the traces leave the simulations however the steps end
    Simulation &a, &b;
    ~Attached() { a.trace_ = b.trace_ = nullptr; }
  } attached{a, b};
  a.trace_ = &ta;
  b.trace_ = &tb;
  std::string found;
  for (std::int64_t k = 0; k < steps && found.empty(); ++k) {
    const bool then_predict = k + 1 < steps;
    a.advance(then_predict);
    b.advance(then_predict);
    found = compare_matched(ta, tb, a.world().s.step);
  }
  return found;
}

}  // namespace gs

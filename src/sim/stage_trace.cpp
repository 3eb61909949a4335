#include "sim/stage_trace.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "sim/stages.hpp"

namespace gs {
namespace {

// field k of the step's state or forces
const std::vector<double>& trace_source(const StepContext& c, std::size_t k) {
  const State& s = c.p().w.s;
  const ForceBuffer& f = c.p().forces;
  const std::array<const std::vector<double>*, StageTrace::kFields> src{
      &s.x, &s.y, &s.th, &s.vx, &s.vy, &s.omega, &s.ax, &s.ay, &s.alpha, &f.fx, &f.fy, &f.tq};
  return *src[k];
}

std::string trace_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

const std::array<const char*, StageTrace::kFields>& StageTrace::field_names() {
  static const std::array<const char*, kFields> names{"x",  "y",  "th",    "vx", "vy", "omega",
                                                      "ax", "ay", "alpha", "fx", "fy", "tq"};
  return names;
}

void StageTrace::open(Stage s, const StepContext& c) {
  if (s == Stage::Drive || s == Stage::Health || s == Stage::PlaceNext) return;
  Record r;
  r.step = c.p().w.s.step;
  r.ran = s;
  r.as = s;
  if (s == Stage::PredictNext || (s == Stage::Kick && c.ahead)) {
    r.step += 1;
    r.as = Stage::Predict;
  } else if (s == Stage::Kick) {
    r.as = Stage::Correct;
  }
  for (auto& f : r.fields) f.assign(c.p().w.size(), 0.0);
  open_[static_cast<std::size_t>(s)] = static_cast<int>(records_.size());
  records_.push_back(std::move(r));
}

void StageTrace::take(Stage s, const StepContext& c, std::size_t b, std::size_t e) {
  const int at = open_[static_cast<std::size_t>(s)];
  if (at < 0) return;
  Record& r = records_[static_cast<std::size_t>(at)];
  for (std::size_t k = 0; k < kFields; ++k) {
    const std::vector<double>& src = trace_source(c, k);
    const std::size_t end = std::min({e, src.size(), r.fields[k].size()});
    for (std::size_t i = b; i < end; ++i) r.fields[k][i] = src[i];
  }
}

void StageTrace::close(Stage s, const StepContext& c) {
  int& at = open_[static_cast<std::size_t>(s)];
  if (at < 0) return;
  Record& r = records_[static_cast<std::size_t>(at)];
  if (s == Stage::BroadPhase) r.pairs = *c.candidates;
  if (s == Stage::Pairs) r.pairs = c.p().contacts.keys;
  at = -1;
}

std::string first_difference(const StageTrace::Record& a, const StageTrace::Record& b) {
  const std::size_t n = std::min(a.fields[0].size(), b.fields[0].size());
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < StageTrace::kFields; ++k) {
      const double p = a.fields[k][i], q = b.fields[k][i];
      if (std::memcmp(&p, &q, sizeof p) != 0)
        return "particle " + std::to_string(i) + ", field " + StageTrace::field_names()[k] + ": " +
               trace_number(p) + " vs " + trace_number(q);
    }
  }
  if (a.fields[0].size() != b.fields[0].size())
    return "particle count: " + std::to_string(a.fields[0].size()) + " vs " +
           std::to_string(b.fields[0].size());
  const char* list = a.ran == Stage::BroadPhase ? "candidate" : "contact";
  const std::size_t m = std::min(a.pairs.size(), b.pairs.size());
  for (std::size_t k = 0; k < m; ++k) {
    if (a.pairs[k] != b.pairs[k])
      return "particle " + std::to_string(key_i(std::min(a.pairs[k], b.pairs[k]))) + ", " + list +
             " " + std::to_string(k) + ": partner " + std::to_string(key_j(a.pairs[k])) + " vs " +
             std::to_string(key_j(b.pairs[k]));
  }
  if (a.pairs.size() != b.pairs.size())
    return std::string(list) + " count: " + std::to_string(a.pairs.size()) + " vs " +
           std::to_string(b.pairs.size());
  return {};
}

}  // namespace gs

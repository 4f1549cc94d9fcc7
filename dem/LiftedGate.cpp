#include "LiftedGate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "Dictionary.h"
#include "LiggghtsCommands.h"

namespace mixflow::dem {

namespace {
std::string fmt(double v) { return formatNumber(v, 15); }
}  // namespace

LiftedGate::LiftedGate(const Scene& s, double settledHeight) : scene_(s) {
  const double d = s.particles.diameter;
  // The tallest grain tops lie within a diameter of the mean column top.
  removalHeight_ = settledHeight + 2 * d;
  plateHeight_ = settledHeight + 3 * d;
}

std::string LiftedGate::stl(double lowerEdge) const {
  const Scene& s = scene_;
  const double d = s.particles.diameter;
  const double y0 = lowerEdge, y1 = lowerEdge + plateHeight_;
  // Across a periodic width the plate stops 1e-2 d short of the boundary planes; no grain passes a
  // gap of 2e-2 d.
  const double gap = s.channel.sideWalls == "periodic" ? 1e-2 * d : 0.0;
  const double z0 = gap, z1 = s.sample.width - gap;
  // LIGGGHTS bins a mesh's elements in its bounding box, which must not be flat: the top edge
  // leans downstream by 1e-3 d (an angle of about 1e-4, nothing a grain feels). Its mesh
  // neighbour list also fails on elements much larger than a grain in a narrow periodic box
  // (measured: one element across a 0.072-0.2 m slice), so the plate is cut into squares of
  // about d.
  const double lean = 1e-3 * d;
  auto x = [&](double y) { return s.sample.length + lean * (y - y0) / (y1 - y0); };
  const int ny = std::max(1, static_cast<int>(std::ceil((y1 - y0) / d)));
  const int nz = std::max(1, static_cast<int>(std::ceil((z1 - z0) / d)));
  std::ostringstream o;
  auto vertex = [&](double y, double z) {
    o << "  vertex " << fmt(x(y)) << " " << fmt(y) << " " << fmt(z) << "\n";
  };
  o << "solid gate\n";
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < ny; ++j) {
      const double za = z0 + (z1 - z0) * i / nz, zb = z0 + (z1 - z0) * (i + 1) / nz;
      const double ya = y0 + (y1 - y0) * j / ny, yb = y0 + (y1 - y0) * (j + 1) / ny;
      for (const auto& tri :
           {std::array<std::pair<double, double>, 3>{{{ya, za}, {yb, za}, {yb, zb}}},
            std::array<std::pair<double, double>, 3>{{{ya, za}, {yb, zb}, {ya, zb}}}}) {
        o << "facet normal 1 0 0\n outer loop\n";
        for (const auto& [y, z] : tri) vertex(y, z);
        o << " endloop\nendfacet\n";
      }
    }
  o << "endsolid gate\n";
  return o.str();
}

namespace {
// t = (step - step0) dt as an equal-style expression.
std::string timeOf(double dt, long step0) {
  return "((step-" + std::to_string(step0) + ")*" + fmt(dt) + ")";
}
}  // namespace

double LiftedGate::parkTime() const {
  const GateSpec& g = scene_.gate;
  const double hp = removalHeight_;
  if (g.speed >= 0) return g.speed > 0 ? hp / g.speed : -1;
  if (g.lift.front().second >= hp) return 0;
  for (size_t i = 1; i < g.lift.size(); ++i) {
    const auto& [t0, h0] = g.lift[i - 1];
    const auto& [t1, h1] = g.lift[i];
    if (h1 >= hp && h1 > h0) return t0 + (t1 - t0) * (hp - h0) / (h1 - h0);
  }
  return -1;
}

std::string LiftedGate::speedFormula(double dt, long step0, bool parked) const {
  const GateSpec& g = scene_.gate;
  const std::string t = timeOf(dt, step0);
  std::string f;
  if (g.speed >= 0) {
    f = fmt(g.speed);
  } else {
    // Between two points of the table the edge rises at their slope; before and after, it rests.
    for (size_t i = 1; i < g.lift.size(); ++i) {
      const auto& [t0, h0] = g.lift[i - 1];
      const auto& [t1, h1] = g.lift[i];
      if (!f.empty()) f += "+";
      f += "(" + t + ">=" + fmt(t0) + ")*(" + t + "<" + fmt(t1) + ")*" + fmt((h1 - h0) / (t1 - t0));
    }
    if (f.empty()) f = "0";
  }
  const double tp = parkTime();
  if (parked && tp >= 0) f = "(" + t + "<" + fmt(tp) + ")*(" + f + ")";
  return f;
}

std::string LiftedGate::parkedHeightFormula(double dt, long step0) const {
  const GateSpec& g = scene_.gate;
  const std::string t = timeOf(dt, step0);
  std::string h;
  if (g.speed >= 0) {
    h = t + "*" + fmt(g.speed);
  } else {
    h = "(" + t + "<" + fmt(g.lift.front().first) + ")*" + fmt(g.lift.front().second);
    for (size_t i = 1; i < g.lift.size(); ++i) {
      const auto& [t0, h0] = g.lift[i - 1];
      const auto& [t1, h1] = g.lift[i];
      h += "+(" + t + ">=" + fmt(t0) + ")*(" + t + "<" + fmt(t1) + ")*(" + fmt(h0) + "+" +
           fmt((h1 - h0) / (t1 - t0)) + "*(" + t + "-" + fmt(t0) + "))";
    }
    h += "+(" + t + ">=" + fmt(g.lift.back().first) + ")*" + fmt(g.lift.back().second);
  }
  // The smaller of h and the parking height, without min() (a compute function in LIGGGHTS).
  const std::string p = fmt(removalHeight_);
  return "((" + h + ")<" + p + ")*(" + h + ")+((" + h + ")>=" + p + ")*" + p;
}

std::vector<std::string> LiftedGate::plateCommands(const std::string& stlFile,
                                                   const std::string& meshOptions,
                                                   const std::string& speed) const {
  const Scene& s = scene_;
  return {"fix gateMesh all mesh/surface file " + stlFile + " type " + std::to_string(kWallType) +
              meshOptions,
          "fix wGateLifted all wall/gran " + contactModel(s.particles) +
              " mesh n_meshes 1 meshes gateMesh " + contactSettings(s.dem.limitForce),
          "variable gateSpeed equal " + speed, "variable gateStill equal 0",
          "fix gateMove all move/mesh mesh gateMesh linear/variable v_gateStill v_gateSpeed "
          "v_gateStill"};
}

std::vector<std::string> LiftedGate::parkedCommands(const std::string& stlFile, double dt) const {
  std::vector<std::string> c = {"variable gateLift equal " + parkedHeightFormula(dt, 0)};
  for (auto& line : plateCommands(stlFile, " move 0 ${gateLift} 0", speedFormula(dt, 0, true)))
    c.push_back(line);
  return c;
}

std::vector<std::string> LiftedGate::commands(const std::string& stlFile, double dt,
                                              long step0) const {
  return plateCommands(stlFile, "", speedFormula(dt, step0));
}

std::vector<std::string> LiftedGate::removeCommands() {
  return {"unfix gateMove", "unfix wGateLifted", "unfix gateMesh"};
}

}  // namespace mixflow::dem

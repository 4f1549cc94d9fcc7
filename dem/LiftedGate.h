// A lifted gate for the grains (sceneProperties gate { removal lifted; ... }): a rigid plate in the
// plane x = L, as tall as the settled column and a margin, whose lower edge follows the scene's law
// h(t). It is a LIGGGHTS mesh wall (fix mesh/surface) moved by fix move/mesh linear/variable at
// the law's speed. mixflowDem removes it once its lower edge has passed every grain of the column;
// a coupled run's script (mixflowPrepare) parks it there instead, so the same script lines serve
// a fresh start and a resume.
#pragma once

#include <string>
#include <vector>

#include "Scene.h"

namespace mixflow::dem {

class LiftedGate {
 public:
  // settledHeight: the settled column's height (m); its tallest grains lie within a diameter.
  LiftedGate(const Scene& s, double settledHeight);

  // The plate's lower edge at t = 0 is h(0); the plate spans lower edge .. + plateHeight().
  double plateHeight() const { return plateHeight_; }
  // Above this lower edge no grain of the column can touch the plate: it is removed.
  double removalHeight() const { return removalHeight_; }
  bool removedAt(double t) const { return scene_.gate.height(t) > removalHeight_; }

  // The plate (squares of about d cut in two triangles, ASCII STL), its lower edge at lowerEdge.
  std::string stl(double lowerEdge) const;
  // The mesh, its wall and its motion from the restart or the opening at step*dt = t on; the
  // motion reads the law's speed at t = (step - step0) dt, step0 being the opening's step.
  std::vector<std::string> commands(const std::string& stlFile, double dt, long step0) const;
  static std::vector<std::string> removeCommands();
  // The script lines of a coupled run (step 0 = the opening): the plate read from stlFile
  // (written with its lower edge at 0) moved to h(t) at the script's step, then at dh/dt until
  // its edge reaches removalHeight(), where it stays.
  std::vector<std::string> parkedCommands(const std::string& stlFile, double dt) const;

 private:
  // The equal-style formula of dh/dt at t = (step - step0) dt (piecewise constant), zero from
  // parkTime on when parked.
  std::string speedFormula(double dt, long step0, bool parked = false) const;
  // The equal-style formula of h(t), at most removalHeight().
  std::string parkedHeightFormula(double dt, long step0) const;
  // The first time h(t) reaches removalHeight() (< 0: never).
  double parkTime() const;
  // The mesh (from stlFile, with meshOptions), its wall and its motion at the formula speed.
  std::vector<std::string> plateCommands(const std::string& stlFile, const std::string& meshOptions,
                                         const std::string& speed) const;

  const Scene& scene_;
  double plateHeight_ = 0, removalHeight_ = 0;
};

}  // namespace mixflow::dem

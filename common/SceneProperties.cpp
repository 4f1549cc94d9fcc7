#include "SceneProperties.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace mixflow {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::string num(double v) { return formatNumber(v, 6); }

// Plausible ranges (Param::plausible): values outside are refused as unit slips before anything
// runs. Lengths of a laboratory or field scene; moduli from soft rubber (1e5 Pa) to diamond
// (1.2e12 Pa); liquids from liquid hydrogen (71 kg/m3, 1.3e-5 Pa s) on; a gas pore fluid (the
// bulk model's dry scene P-bulk: air) has density <= kGasDensityMax and viscosity
// <= kGasViscosityMax.
const Range kLengths = Range::closed(1e-3, 100.0);
const std::vector<UnitSlip> kLengthSlips{{"mm", 1e-3}, {"cm", 1e-2}};
const Range kModuli = Range::closed(1e5, 1.2e12);
const std::vector<UnitSlip> kModulusSlips{{"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}};
constexpr double kLiquidDensityMin = 50;
constexpr double kLiquidViscosityMin = 1e-5;
constexpr double kGasDensityMax = 10;
constexpr double kGasViscosityMax = 1e-4;

Schema makeSchema() {
  const SampleSpec s{};
  const ChannelSpec c{};
  const ParticleMaterial p{};
  const AirProperties a{};
  const GateSpec g{};
  const SceneProperties scene{};
  const std::vector<std::string> yieldStress{"HerschelBulkley", "Bingham"};
  return Schema(
      "constant/sceneProperties",
      {
          requiredWord("content", {"particles", "liquid", "mixture"},
                       "what the scene holds: grains (LIGGGHTS only, mixflowDem), a liquid "
                       "(mixflowFoam; mixflowPrepare refuses particles) or both (the liquid fills "
                       "the sample box; the grains' voidfraction comes from the coupling)"),
          dictParam("sample", "the column behind the gate at x = L; back wall at x = 0"),
          requiredScalar("sample.length", Range::positive(), "m",
                         "L of the column behind the gate (back wall at x = 0, gate at x = L)")
              .alsoAllowed("≥ d with grains")
              .plausible(kLengths, "a laboratory or field dam-break scene", kLengthSlips),
          requiredScalar("sample.height", Range::positive(), "m", "H of the column")
              .alsoAllowed("≥ d with grains")
              .plausible(kLengths, "a laboratory or field dam-break scene", kLengthSlips),
          requiredScalar("sample.width", Range::positive(), "m",
                         "W; also the channel width (side walls at z = 0, W)")
              .alsoAllowed("≥ d with grains")
              .plausible(kLengths, "a laboratory or field dam-break scene", kLengthSlips),
          // Above random close packing (0.64) a monodisperse sample cannot be made by settling.
          scalarParam(
              "sample.solidFraction", s.solidFraction, Range::openClosed(0.0, 0.64), "",
              "φ of the grains (Li & Zhao): N = φ L H W / V_p particles, and the settled "
              "sample's fraction N V_p / (L W h) within demDict settle.packingTolerance "
              "(0.003) at every tier and softening: the packing control "
              "(settle.packingControl) tunes the settling friction, else the preparation "
              "stops naming the entries to change. With packingControl off it sets the "
              "count only (settle.friction 0.1: 0.606 at the reference tier, 0.629 at the "
              "quick tier) and the settle warns 3 % off. Validated, and unused, in a liquid "
              "scene"),
          dictParam("channel", "the channel downstream of the gate"),
          requiredScalar("channel.length", Range::positive(), "m",
                         "x of the outlet: particles beyond are deleted, the liquid leaves "
                         "(zero-gradient U and p). Paper: not given; the dry cases use 4.0 m, "
                         "the liquid and mixture cases 5.86 m (calibrated with case W, below)")
              .alsoAllowed("> L (with grains > L + d)")
              .plausible(kLengths, "a laboratory or field dam-break scene", kLengthSlips),
          requiredScalar("channel.height", Range::positive(), "m",
                         "y of the open top: particles above are deleted, the atmosphere of the "
                         "liquid. It must lie above the column: a liquid needs air above it, and "
                         "grains standing at H are not deleted. Paper: not given; cases use 1.2 m")
              .alsoAllowed("> H")
              .plausible(kLengths, "a laboratory or field dam-break scene", kLengthSlips),
          wordParam("channel.sideWalls", c.sideWalls, {"walls", "periodic"},
                    "walls: frictional (grains) and no-slip (liquid) side walls at z = 0, W "
                    "(paper); periodic: an infinitely wide channel (cyclic z faces of a 3-D "
                    "liquid). 2-D liquid: ignored (no side walls)"),
          scalarParam("channel.liquidDepth", c.liquidDepth, Range::nonNegative(), "m",
                      "still liquid standing over the whole channel floor at t = 0, up to this "
                      "depth: the column collapses immersed in a tank (Rondon, Pouliquen & "
                      "Aussillous 2011), and the outlet is a closed wall. 0: a dry channel with "
                      "an open outlet (the paper's). Liquid and mixture scenes")
              .alsoAllowed("< channel height; 0 in a dry scene"),
          dictParam("gate",
                    "the gate at x = L that holds the column until t = 0 (optional: removed at "
                    "once)"),
          wordParam("gate.removal", g.removal, {"instant", "lifted"},
                    "instant: the gate is gone at t = 0 (the paper's); lifted: a plate at "
                    "x = L whose lower edge rises from the channel floor as h(t) (`speed` or "
                    "`lift`), the liquid leaving below it (mixflowFoam, implicit momentum sink "
                    "in the plate's cells whose centres lie above h; cfd/README.md) and the "
                    "grains held by it until it passes (mixflowDem, a LIGGGHTS mesh wall "
                    "moved by fix move/mesh; dem/README.md), both in a mixture"),
          scalarParam("gate.speed", 0, Range::nonNegative(), "m/s",
                      "lifted: h(t) = speed t (0: a plate that never lifts); give `speed` or "
                      "`lift`, not both")
              .only({"lifted"})
              .shownDefault("(lifted: speed or lift)")
              .plausible(Range::closed(0.0, 100.0), "a gate lifted by hand or by a machine",
                         {{"mm/s", 1e-3}, {"cm/s", 1e-2}}),
          textParam("gate.lift", "",
                    "lifted: the table ((t0 h0) (t1 h1) ...) of the lower edge's height h (m "
                    "above the floor) against t (s): linear between points, h0 before t0 and "
                    "the last h after the last point")
              .only({"lifted"})
              .shownDefault("(lifted: speed or lift)")
              .alsoAllowed("t ≥ 0 increasing, h ≥ 0"),
          autoScalar(
              "gate.thickness", Range::positive(), "m",
              "lifted, liquid: the plate spans L ≤ x < L + thickness, its cells are those whose "
              "centres lie in it; auto: two cells (cfdDict cellSize). One cell lets the "
              "liquid through: a face's 1/A in the pressure equation is the mean of its "
              "two cells', so the faces to the free cells are half open (measured 28 % "
              "of a held column beyond a one-cell plate after 0.2 s)")
              .only({"lifted"})
              .alsoAllowed("≥ two cells, < channel length − L"),
          dictParam("particles", "the grains (Table 3); moduli before softening"),
          scalarParam("particles.diameter", p.diameter, Range::positive(), "m", "d (Table 3)")
              .plausible(Range::closed(1e-5, 0.5), "a grain, from silt to boulders",
                         {{"mm", 1e-3}, {"cm", 1e-2}}),
          // Grains from expanded polystyrene beads to osmium; one like 1e300 overflows the
          // particle mass inside LIGGGHTS.
          scalarParam("particles.density", p.density, Range::closed(10.0, 25000.0), "kg/m3",
                      "solid grains from expanded polystyrene beads (about 15) to osmium "
                      "(22 600); a value outside is a typo, and one like 1e300 overflows the "
                      "particle mass inside LIGGGHTS")
              .plausible(Range::closed(10.0, 25000.0), "a solid grain", {{"g/cm³", 1e3}}),
          scalarParam("particles.youngModulus", p.youngModulus, Range::positive(), "Pa",
                      "particle material (before softening)")
              .plausible(kModuli, "a grain's material, from soft rubber to diamond", kModulusSlips),
          scalarParam("particles.wallYoungModulus", p.wallYoungModulus, Range::positive(), "Pa",
                      "wall material. **Open choice**: the paper's \"700 GPa (particle-wall)\" is "
                      "taken as the wall material's modulus, so the particle-wall contact modulus "
                      "E* is 6.99e10 Pa, not 700 GPa")
              .plausible(kModuli, "a wall's material, from soft rubber to diamond", kModulusSlips),
          scalarParam("particles.poissonRatio", p.poisson, {0.0, 0.5, false, true}, "",
                      "both materials"),
          // LIGGGHTS' damping formula needs e > 0; e = 1 is elastic.
          scalarParam("particles.restitution", p.restitution, Range::openClosed(0.0, 1.0), "",
                      "particle-particle and particle-wall"),
          scalarParam("particles.friction", p.friction, Range::nonNegative(), "",
                      "particle-particle"),
          scalarParam("particles.wallFriction", p.wallFriction, Range::nonNegative(), "",
                      "particle-wall (bottom, back, sides)"),
          scalarParam("particles.rollingFriction", p.rollingFriction, Range::nonNegative(), "",
                      "μ_r"),
          wordParam("particles.rollingModel", p.rollingModel, {"cdt", "epsd2", "off"},
                    "**Open choice**: the paper cites a rolling-friction model without naming "
                    "it. cdt = constant directional torque μ_r R F_n (a rolling sphere "
                    "decelerates at 5/7 μ_r g)"),
          scalarParam("particles.rollingViscousDamping", p.rollingViscousDamping,
                      Range::nonNegative(), "", "only for epsd-type models"),
          dictParam("liquid", "the liquid (Table 2, SI units); its rheology selects its entries"),
          requiredWord("liquid.rheology", {"Newtonian", "HerschelBulkley", "Bingham"},
                       "τ = τc + κ γ̇ⁿ (docs/model.md §5)"),
          requiredScalar("liquid.density", Range::positive(), "kg/m3", "ρ")
              .alsoAllowed("> air density")
              .plausible(Range::closed(kLiquidDensityMin, 25000.0),
                         "a liquid, from liquid hydrogen (71) to mercury (13 534) and beyond; a "
                         "gas pore fluid (density ≤ 10, Newtonian viscosity ≤ 1e-4 Pa s, e.g. "
                         "air in cases/P-bulk) is taken too",
                         {{"g/cm³", 1e3}}, true),
          requiredScalar("liquid.viscosity", Range::positive(), "Pa s", "μ")
              .plausible(Range::closed(kLiquidViscosityMin, 1e8),
                         "a liquid's dynamic viscosity, from liquid hydrogen (1.3e-5) to pitch; "
                         "a value that is ρ ν in range (ν typed in m²/s) is named so; not checked "
                         "for a gas pore fluid",
                         {{"mPa s", 1e-3}}, true)
              .only({"Newtonian"})
              .shownDefault("(required, Newtonian only)"),
          requiredScalar("liquid.yieldStress", Range::nonNegative(), "Pa", "τc")
              .only(yieldStress)
              .shownDefault("(required, HB and Bingham)"),
          requiredScalar("liquid.consistency", Range::positive(), "Pa s^n",
                         "κ. Bingham: synonym of `plasticViscosity`")
              .only(yieldStress)
              .shownDefault("(required, HB)"),
          requiredScalar("liquid.flowIndex", Range::positive(), "",
                         "n. Bingham: n = 1 (any other value is refused)")
              .only(yieldStress)
              .shownDefault("(required, HB)"),
          requiredScalar("liquid.plasticViscosity", Range::positive(), "Pa s",
                         "μp; give it or `consistency`, not both")
              .only({"Bingham"})
              .shownDefault("(required, Bingham)"),
          // OpenFOAM's HerschelBulkley caps the apparent viscosity,
          // nu = min(nu0, (tau0 + k gamma_dot^n) / gamma_dot).
          scalarParam("liquid.viscosityCap", 1e4, Range::positive(), "Pa s",
                      "regularisation μ0: the apparent viscosity is min(μ0, (τc + κ γ̇ⁿ)/γ̇) "
                      "(OpenFOAM's `HerschelBulkley`, nu0 = μ0/ρ). **Open choice**, below")
              .only(yieldStress)
              .alsoAllowed("> τc + κ (the apparent viscosity at 1/s)"),
          scalarParam("liquid.surfaceTension", scene.surfaceTension, Range::nonNegative(), "N/m",
                      "σ liquid-air; the paper gives none (water-air value)"),
          dictParam("liquid.air", "the air above the liquid (Table 2)"),
          scalarParam("liquid.air.density", a.density, Range::positive(), "kg/m3", "Table 2"),
          scalarParam("liquid.air.viscosity", a.viscosity, Range::positive(), "Pa s",
                      "Table 2: κ = 1.48e-5, n = 1"),
      });
}

void readSample(const Schema& sc, const Dictionary& d, SampleSpec& s) {
  sc.allowOnly(d, "sample");
  s.length = sc.scalar(d, "sample.length");
  s.height = sc.scalar(d, "sample.height");
  s.width = sc.scalar(d, "sample.width");
  s.solidFraction = sc.scalar(d, "sample.solidFraction");
}

void readChannel(const Schema& sc, const Dictionary& d, ChannelSpec& c) {
  sc.allowOnly(d, "channel");
  c.length = sc.scalar(d, "channel.length");
  c.height = sc.scalar(d, "channel.height");
  c.sideWalls = sc.word(d, "channel.sideWalls");
  c.liquidDepth = sc.scalar(d, "channel.liquidDepth");
}

void readParticles(const Schema& sc, const Dictionary& d, ParticleMaterial& p) {
  sc.allowOnly(d, "particles");
  p.diameter = sc.scalar(d, "particles.diameter");
  p.density = sc.scalar(d, "particles.density");
  p.youngModulus = sc.scalar(d, "particles.youngModulus");
  p.wallYoungModulus = sc.scalar(d, "particles.wallYoungModulus");
  p.poisson = sc.scalar(d, "particles.poissonRatio");
  p.restitution = sc.scalar(d, "particles.restitution");
  p.friction = sc.scalar(d, "particles.friction");
  p.wallFriction = sc.scalar(d, "particles.wallFriction");
  p.rollingFriction = sc.scalar(d, "particles.rollingFriction");
  p.rollingModel = sc.word(d, "particles.rollingModel");
  p.rollingViscousDamping = sc.scalar(d, "particles.rollingViscousDamping");
}

bool contains(const std::vector<std::string>& v, const std::string& k) {
  for (const auto& w : v)
    if (w == k) return true;
  return false;
}

// The gate's entries depend on its removal; one of speed and lift gives a lifted gate's law.
void readGate(const Schema& sc, const Dictionary& d, GateSpec& g) {
  g.removal = sc.word(d, "gate.removal");
  const std::vector<std::string> allowed = sc.keys("gate", g.removal);
  for (const auto& k : d.keys())
    if (!contains(allowed, k) && contains(sc.keys("gate"), k))
      d.fail(k, "is not a parameter of removal " + g.removal +
                    "; its entries are: " + joinWords(allowed));
  d.allowOnly(allowed);
  if (!g.lifted()) return;
  const bool hasSpeed = d.has("speed"), hasLift = d.has("lift");
  if (hasSpeed == hasLift)
    d.fail(hasSpeed ? "lift" : "speed",
           std::string(hasSpeed ? "give either speed or lift, not both"
                                : "missing (required): a lifted gate needs speed (m/s), "
                                  "allowed range [0, inf), or the table lift ((t0 h0) ...)"));
  if (hasSpeed) {
    g.speed = sc.scalar(d, "gate.speed");
  } else {
    const std::vector<double> v = d.scalars("lift", Range::nonNegative());
    if (v.empty() || v.size() % 2 != 0)
      d.fail("lift", "needs (t h) pairs, ((t0 h0) (t1 h1) ...), at least one; got " +
                         std::to_string(v.size()) + " numbers");
    for (size_t i = 0; i < v.size(); i += 2) {
      if (i > 0 && v[i] <= v[i - 2])
        d.fail("lift", "time " + num(v[i]) + " s follows " + num(v[i - 2]) +
                           " s; the times must increase, allowed range (" + num(v[i - 2]) +
                           ", inf)");
      g.lift.emplace_back(v[i], v[i + 1]);
    }
  }
  if (const auto t = sc.scalarOrAuto(d, "gate.thickness")) g.thickness = *t;
}

// The liquid's entries depend on its rheology; an entry of another rheology is named as such
// (e.g. yieldStress for a Newtonian liquid), not just as "unknown".
void readLiquid(const Schema& sc, const Dictionary& d, SceneProperties& s) {
  Rheology& r = s.liquid;
  r.model = sc.word(d, "liquid.rheology");
  const std::vector<std::string> allowed = sc.keys("liquid", r.model);
  for (const auto& k : d.keys())
    if (!contains(allowed, k) && contains(sc.keys("liquid"), k))
      d.fail(k, "is not a parameter of rheology " + r.model +
                    "; its entries are: " + joinWords(allowed));
  d.allowOnly(allowed);

  r.density = sc.scalar(d, "liquid.density");
  if (r.model == "Newtonian") {
    r.viscosity = sc.scalar(d, "liquid.viscosity");
  } else {
    r.yieldStress = sc.scalar(d, "liquid.yieldStress");
    if (r.model == "HerschelBulkley") {
      r.consistency = sc.scalar(d, "liquid.consistency");
      r.flowIndex = sc.scalar(d, "liquid.flowIndex");
    } else {
      // Bingham: tau = tau_c + mu_p gamma_dot, i.e. Herschel-Bulkley with n = 1.
      const bool hasMu = d.has("plasticViscosity"), hasK = d.has("consistency");
      if (hasMu && hasK)
        d.fail("consistency",
               "give either plasticViscosity or consistency (the same coefficient for "
               "Bingham), not both");
      if (!hasMu && !hasK)
        d.fail("plasticViscosity",
               "missing (required): a Bingham liquid needs plasticViscosity (Pa s), allowed "
               "range (0, inf) (or consistency, its synonym)");
      r.consistency = sc.scalar(d, hasMu ? "liquid.plasticViscosity" : "liquid.consistency");
      if (d.has("flowIndex")) {
        const double n = sc.scalar(d, "liquid.flowIndex");
        if (n != 1.0)
          d.fail("flowIndex", "value " + num(n) +
                                  ": a Bingham liquid has n = 1 (remove the entry, or use "
                                  "rheology HerschelBulkley)");
      }
      r.flowIndex = 1.0;
    }
    r.viscosityCap = sc.scalar(d, "liquid.viscosityCap");
    const double mu1 = r.yieldStress + r.consistency;  // apparent viscosity at 1/s (Pa s)
    if (r.viscosityCap <= mu1)
      d.fail("viscosityCap", "value " + num(r.viscosityCap) +
                                 " Pa s must exceed the apparent viscosity at a shear rate of "
                                 "1/s, yieldStress + consistency = " +
                                 num(mu1) +
                                 " Pa s (a lower cap replaces the rheology by a Newtonian "
                                 "liquid where it matters); allowed range (" +
                                 num(mu1) + ", inf)");
  }
  s.surfaceTension = sc.scalar(d, "liquid.surfaceTension");

  const Dictionary a = d.subDictOrEmpty("air");
  sc.allowOnly(a, "liquid.air");
  s.air.density = sc.scalar(a, "liquid.air.density");
  s.air.viscosity = sc.scalar(a, "liquid.air.viscosity");
  if (s.air.density >= r.density)
    d.fail("density", "value " + num(r.density) + " must exceed the air density (" +
                          num(s.air.density) + " kg/m3): the liquid lies under the air");
  // Plausibility: a liquid, or a gas pore fluid (light and thin: air in a dry bulk-model scene).
  const bool gas =
      r.model == "Newtonian" && r.density <= kGasDensityMax && r.viscosity <= kGasViscosityMax;
  if (gas) return;
  if (r.density <= kGasDensityMax && r.model == "Newtonian" && r.viscosity > kGasViscosityMax &&
      !sc.param("liquid.density").slipHint(r.density).empty())
    d.fail("density", "value " + num(r.density) + " kg/m3 is a gas's density, but viscosity " +
                          num(r.viscosity) + " Pa s is a liquid's" +
                          sc.param("liquid.density").slipHint(r.density) +
                          "; a liquid's plausible range is [" + num(kLiquidDensityMin) +
                          ", 25000] kg/m3, a gas pore fluid's (0, " + num(kGasDensityMax) +
                          "] kg/m3 with viscosity <= " + num(kGasViscosityMax) +
                          " Pa s (docs/parameters.md, \"Plausible ranges\")");
  sc.checkPlausible(d, "liquid.density", r.density);
  if (r.model == "Newtonian" &&
      !sc.param("liquid.viscosity").plausibleRange->contains(r.viscosity) &&
      r.viscosity * r.density >= kLiquidViscosityMin && r.viscosity < kLiquidViscosityMin)
    d.fail("viscosity",
           "value " + num(r.viscosity) + " Pa s is outside the plausible range " + "[" +
               num(kLiquidViscosityMin) + ", 1e8]" +
               " Pa s of a liquid's dynamic viscosity (a unit slip? as the kinematic viscosity "
               "ν in m2/s it gives μ = ρ ν = " +
               num(r.viscosity * r.density) + " Pa s); write μ in Pa s");
  if (r.model == "Newtonian") sc.checkPlausible(d, "liquid.viscosity", r.viscosity);
}

// Rules between entries. The outlet lies downstream of the gate, beyond the front grain when
// there are grains; the open top lies above the column: a liquid needs air above it, and a
// grain whose top touches y = H is not in the deletion region of the first pass.
void checkGeometry(const Dictionary& scene, const SceneProperties& s) {
  const Dictionary& sample = scene.subDict("sample");
  const Dictionary& channel = scene.subDict("channel");
  const double d = s.grains() ? s.particles.diameter : 0.0;
  if (s.grains()) {
    const std::pair<const char*, double> sizes[] = {
        {"length", s.sample.length}, {"height", s.sample.height}, {"width", s.sample.width}};
    for (const auto& [key, size] : sizes)
      if (size < d)
        sample.fail(key, "value " + num(size) + " m is below one particle diameter (" + num(d) +
                             " m); allowed range [" + num(d) + ", inf)");
  }
  if (s.channel.length <= s.sample.length + d)
    channel.fail("length", "value " + num(s.channel.length) + " must exceed the sample length" +
                               (s.grains() ? " plus one particle diameter" : "") + " (" +
                               num(s.sample.length + d) +
                               " m): the outlet lies downstream of the gate");
  if (s.channel.height <= s.sample.height)
    channel.fail("height", "value " + num(s.channel.height) + " must exceed the sample height (" +
                               num(s.sample.height) + " m): the open top lies above the column");
  if (s.channel.tank() && !s.fluid())
    channel.fail("liquidDepth", "value " + num(s.channel.liquidDepth) +
                                    " m needs a liquid: content " + s.content +
                                    " has none; allowed value 0");
  if (s.channel.liquidDepth >= s.channel.height)
    channel.fail("liquidDepth", "value " + num(s.channel.liquidDepth) +
                                    " must lie below the channel height (" + num(s.channel.height) +
                                    " m): the liquid needs air above it; "
                                    "allowed range [0, " +
                                    num(s.channel.height) + ")");
  // The grains' lifted plate (as tall as the column and 3 d) rises until its lower edge passes the
  // column (2 d above it) inside the DEM box, whose top is at least 1.5 times the channel height.
  const double plateTop = 2 * s.sample.height + 5 * d;
  if (s.grains() && s.gate.lifted() && plateTop >= 1.5 * s.channel.height)
    channel.fail("height", "value " + num(s.channel.height) + " is too low for a lifted gate: " +
                               "the plate rises to " + num(plateTop) +
                               " m (twice the sample height and 5 d); allowed range (" +
                               num(plateTop / 1.5) + ", inf)");
}
}  // namespace

double GateSpec::height(double t) const {
  if (!lifted()) return 0;
  if (speed >= 0) return speed * std::max(t, 0.0);
  if (t <= lift.front().first) return lift.front().second;
  for (size_t i = 1; i < lift.size(); ++i)
    if (t <= lift[i].first) {
      const auto& [t0, h0] = lift[i - 1];
      const auto& [t1, h1] = lift[i];
      return h0 + (h1 - h0) * (t - t0) / (t1 - t0);
    }
  return lift.back().second;
}

double ParticleMaterial::volume() const { return kPi / 6.0 * diameter * diameter * diameter; }
double ParticleMaterial::mass() const { return density * volume(); }

const Schema& SceneProperties::schema() {
  static const Schema s = makeSchema();
  return s;
}

std::string SceneProperties::readContent(const Dictionary& scene) {
  return schema().word(scene, "content");
}

SceneProperties SceneProperties::read(const Dictionary& scene, Half half) {
  const Schema& sc = schema();
  sc.allowOnly(scene, "");
  SceneProperties s;
  s.content = readContent(scene);
  readSample(sc, scene.subDict("sample"), s.sample);
  readChannel(sc, scene.subDict("channel"), s.channel);
  if (s.grains()) readParticles(sc, scene.subDictOrEmpty("particles"), s.particles);
  {
    const Dictionary gate = scene.subDictOrEmpty("gate");
    sc.allowOnly(gate, "gate");  // every removal's entries; readGate names the misplaced ones
    readGate(sc, gate, s.gate);
  }
  if (half == Half::fluid && s.fluid()) readLiquid(sc, scene.subDict("liquid"), s);
  if (half == Half::grains && s.content == "mixture")
    s.liquid.density = sc.scalar(scene.subDict("liquid"), "liquid.density");
  checkGeometry(scene, s);
  return s;
}

}  // namespace mixflow

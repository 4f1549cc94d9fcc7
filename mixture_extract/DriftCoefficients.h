// Mixture variables and drift coefficients of the quasi two-phase model (docs/model.md §9, Pokhrel
// et al. 2017) from a bin's (or region's) window sums, with a validity mask instead of any division
// by a vanishing quantity: an ill-posed value is never computed, it is stored as NaN with its mask
// 0 and the reason bits saying why.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "AveragingGrid.h"
#include "BinAccumulator.h"
#include "ExtractSettings.h"

namespace mixflow::mx {

// Why a value is masked (bit set = condition holds). Stored per bin and window as "mask_reasons".
enum MaskBit : std::uint16_t {
  kNoParticles = 1,          // no particle volume in the bin during the window
  kFewParticleSamples = 2,   // particle samples < thresholds.minParticleSamples
  kNoLiquid = 4,             // no liquid volume (no fluid data or no liquid cell centre in the bin)
  kLowSolidFraction = 8,     // alpha_s < thresholds.minSolidFraction
  kUnsaturated = 16,         // liquid share of the fluid volume < thresholds.minSaturation
  kSmallUs = 32,             // |u_s| < thresholds.minVelocity
  kSmallWs = 64,             // |w_s| < thresholds.minVelocity
  kSmallPs = 128,            // |p_s| < thresholds.minPressure
  kSmallDenominatorU = 256,  // |alpha_s + lambda_u alpha_f| < thresholds.minDenominator
  kSmallDenominatorW = 512,  // |alpha_s + lambda_w alpha_f| < thresholds.minDenominator
  kNoGradient = 1024,        // mass balance: no neighbour in the mixture along x or y
  kLittleLiquid = 2048,      // liquid share of the fluid volume < thresholds.minLiquidShare
  kNoLiquidSurface = 4096,   // the liquid surface above the bin is not inside the grid
  kSmallLoad = 8192,         // |p_s + p_f_excess| < thresholds.minPressure
};
constexpr std::uint16_t kOutsideMixture = kNoParticles | kFewParticleSamples | kNoLiquid |
                                          kLittleLiquid | kLowSolidFraction | kUnsaturated;
// What masks the particle quantities (u_s, w_s, p_s, sigma) and the liquid ones (u_f, w_f, p_f).
constexpr std::uint16_t kParticleMask = kNoParticles | kFewParticleSamples;
constexpr std::uint16_t kLiquidMask = kNoLiquid | kLittleLiquid;

struct MaskBitInfo {
  std::uint16_t bit;
  const char* name;
  const char* meaning;
};
const std::vector<MaskBitInfo>& maskBits();

enum FieldId : int {
  fAlphaS,
  fAlphaF,
  fUs,
  fWs,
  fUf,
  fWf,
  fPf,
  fPs,
  fPsContact,
  fPsKinetic,
  fSigmaXX,
  fSigmaYY,
  fSigmaZZ,
  fSigmaXY,
  fSaturation,
  fLambdaU,
  fLambdaW,
  fLambdaPRaw,
  fLambdaPDensity,
  fUm,
  fWm,
  fPmRaw,
  fPmDensity,
  fLuu,
  fLww,
  fLuw,
  fLu,
  fLw,
  fLpRaw,
  fLpDensity,
  fLetaUFluidCoeff,
  fLetaWFluidCoeff,
  fLetaMSolidCoeff,
  fLetaMFluidCoeff,
  fLetaU,
  fLetaW,
  fLetaM,
  fMassResidual,
  fMassScale,
  fPfHydrostatic,
  fPfExcess,
  fPTotal,
  fPoreRatio,
  fLambdaPKinematic,
  kFieldCount
};

struct FieldDef {
  FieldId id;
  const char* name;  // dataset name
  const char* unit;
  const char* meaning;      // the formula and the weighting
  std::uint16_t invalidIf;  // reason bits that mask it (0: always valid)
};
const FieldDef& fieldDef(FieldId id);
// The fields written for these settings (pressure convention, viscosities given or not).
std::vector<FieldId> outputFields(const ExtractSettings& s);

struct MixtureValues {
  double value[kFieldCount];  // NaN where masked
  std::uint16_t reasons = 0;
  bool valid(FieldId f) const { return (reasons & fieldDef(f).invalidIf) == 0; }
};

// One bin or region: sums over the window, its volume (bin: dx dy W), snapshot and fluid-time
// counts.
MixtureValues mixtureValues(const BinSums& b, double volume, int snapshots, int fluidTimes,
                            const ExtractSettings& s);

// Eq. 9 residual d/dx(alpha_s u_s + alpha_f u_f) + d/dy(alpha_s w_s + alpha_f w_f), i.e. the
// divergence of the mixture flux (alpha_s + lambda alpha_f) u_s, by central differences between
// mixture bins (one-sided at the mixture's edge); sets fMassResidual, fMassScale (|d/dx| + |d/dy|)
// and kNoGradient.
void massBalance(const AveragingGrid& g, std::vector<MixtureValues>& bins);

}  // namespace mixflow::mx

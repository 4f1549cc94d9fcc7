#include "ParticleSnapshot.h"

#include "Dictionary.h"

namespace mixflow::mx {

void ParticleSnapshot::resize(size_t n) {
  for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &mass, &radius}) a->resize(n);
  stress.resize(n);
  id.resize(n);
}

void checkParticles(const ParticleSnapshot& snap) {
  for (size_t i = 0; i < snap.size(); ++i)
    if (!(snap.radius[i] > 0) || !(snap.mass[i] > 0))
      throw InputError(snap.file + ": particle " + std::to_string(i) +
                       " has non-positive radius or mass");
}

}  // namespace mixflow::mx

// Binary particle snapshots: LIGGGHTS `dump custom` with a .bin name, the layout and columns of
// dem/SnapshotFiles.h. Same quantities as the VTK twin (VtkSnapshot.h), at full precision, read
// about as fast as the disk gives the bytes.
#pragma once

#include <string>

#include "ParticleSnapshot.h"

namespace mixflow::mx {

// Reads every rank's chunk of one .bin snapshot. Throws InputError naming the file when it is
// short (truncated), holds another column count, or its chunks disagree with the header.
ParticleSnapshot readBinarySnapshot(const std::string& path, double time);

}  // namespace mixflow::mx

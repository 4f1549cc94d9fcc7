// Re-balances the DEM's x-slab decomposition by particles: LIGGGHTS 3.8 has neither `balance`
// nor `fix balance`, but its Comm keeps the slab boundaries (xsplit) those commands set, so the
// driver sets them at the particles' x-quantiles and migrates the atoms. Only for a grid of
// slabs in x (procgrid N x 1 x 1); other grids are left as they are.
#pragma once

#include <mpi.h>

#include "LiggghtsSession.h"

namespace mixflow::dem {

// Moves the slab boundaries so that each rank holds about the same number of particles; returns
// false (nothing changed) when the grid is not x slabs or there is only one rank.
bool balanceSlabs(LiggghtsSession& lig, MPI_Comm comm);

}  // namespace mixflow::dem

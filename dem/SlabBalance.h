// Re-balances the DEM's x-slab decomposition by particles: LIGGGHTS 3.8 has neither `balance`
// nor `fix balance`, but its Comm keeps the slab boundaries (xsplit) those commands set, so the
// driver sets them at the particles' weighted x-quantiles and migrates the atoms. Only for a grid
// of slabs in x (procgrid N x 1 x 1); other grids are left as they are.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "LiggghtsSession.h"

namespace mixflow::dem {

// What a particle weighs (demDict balanceWeight): 1 each; 1 + half its neighbours within
// r_i + r_j + the neighbour skin (its share of the contact model's pair list); 1 + half its
// contacts. The pair work of a step grows with the pairs, which a grain of the dense column has
// more of than one of the spread tail.
enum class BalanceWeight { particles, pairs, contacts };
BalanceWeight balanceWeight(const std::string& word);  // a demDict balanceWeight word

// Moves the slab boundaries so that each rank holds about the same weight of particles; returns
// false (nothing changed) when the grid is not x slabs or there is only one rank. The weights
// come from the positions alone, so the same grains give the same slabs on any decomposition.
bool balanceSlabs(LiggghtsSession& lig, MPI_Comm comm,
                  BalanceWeight weight = BalanceWeight::particles);

// The slab boundaries as fractions of the box in x (slabs + 1 values from 0 to 1), or empty when
// the grid is not x slabs: a resumed run sets the stopped run's with setSlabSplits.
std::vector<double> slabSplits(LiggghtsSession& lig);
// Sets the boundaries and migrates the atoms (same on every rank); false, nothing changed, when
// the grid is not x slabs of splits.size() - 1 ranks.
bool setSlabSplits(LiggghtsSession& lig, const std::vector<double>& splits);

}  // namespace mixflow::dem

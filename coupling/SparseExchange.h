// Point-to-point exchange of per-rank buffers: rank r sends send[q] to every rank q with a
// non-empty buffer and receives what others sent it (recv[q] from rank q). Only the buffer sizes
// go through a collective (MPI_Alltoall of one int per rank); the data go point to point, so a
// particle's data travel only to the ranks that need them (never an all-gather). The buffer to
// oneself is moved without MPI.
#pragma once

#include <mpi.h>

#include <vector>

namespace mixflow::coupling {

std::vector<std::vector<double>> exchangeBuffers(std::vector<std::vector<double>>& send,
                                                 MPI_Comm comm);

}  // namespace mixflow::coupling

#include "SparseExchange.h"

#include <stdexcept>

namespace mixflow::coupling {

std::vector<std::vector<double>> exchangeBuffers(std::vector<std::vector<double>>& send,
                                                 MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (static_cast<int>(send.size()) != size)
    throw std::invalid_argument("exchangeBuffers: one send buffer per rank required");
  std::vector<int> sendCounts(size), recvCounts(size);
  for (int q = 0; q < size; ++q) sendCounts[q] = q == rank ? 0 : static_cast<int>(send[q].size());
  MPI_Alltoall(sendCounts.data(), 1, MPI_INT, recvCounts.data(), 1, MPI_INT, comm);

  std::vector<std::vector<double>> recv(size);
  std::vector<MPI_Request> requests;
  const int tag = 4711;
  for (int q = 0; q < size; ++q)
    if (recvCounts[q] > 0) {
      recv[q].resize(recvCounts[q]);
      requests.emplace_back();
      MPI_Irecv(recv[q].data(), recvCounts[q], MPI_DOUBLE, q, tag, comm, &requests.back());
    }
  for (int q = 0; q < size; ++q)
    if (sendCounts[q] > 0) {
      requests.emplace_back();
      MPI_Isend(send[q].data(), sendCounts[q], MPI_DOUBLE, q, tag, comm, &requests.back());
    }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  recv[rank].swap(send[rank]);
  return recv;
}

}  // namespace mixflow::coupling

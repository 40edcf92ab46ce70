// Latency and bandwidth between ranks 0 and 1 (a ping-pong), the two message
// parameters of the cost model (tools/mpi_model.py) as this machine has them:
//   mpiexec -n 2 bench/bench_pingpong
// Latency: half the round trip of an 8-byte message; bandwidth: a 4 MiB
// message (about a halo refresh of 20 000 rows) over half its round trip.
// Each is the median of several timed batches.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

// Seconds for one way of a message of `bytes`, the median of `batches` batches of `trips` round trips.
double one_way_seconds(int rank, int bytes, int trips, int batches) {
  std::vector<char> buffer(static_cast<std::size_t>(bytes), 1);
  std::vector<double> per_trip;
  for (int b = 0; b < batches + 1; ++b) {  // the first batch warms up
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = MPI_Wtime();
    for (int t = 0; t < trips; ++t) {
      if (rank == 0) {
        MPI_Send(buffer.data(), bytes, MPI_CHAR, 1, 0, MPI_COMM_WORLD);
        MPI_Recv(buffer.data(), bytes, MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      } else if (rank == 1) {
        MPI_Recv(buffer.data(), bytes, MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        MPI_Send(buffer.data(), bytes, MPI_CHAR, 0, 0, MPI_COMM_WORLD);
      }
    }
    if (b > 0) per_trip.push_back((MPI_Wtime() - start) / trips);
  }
  std::nth_element(per_trip.begin(), per_trip.begin() + per_trip.size() / 2, per_trip.end());
  return 0.5 * per_trip[per_trip.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks < 2) {
    if (rank == 0) std::fprintf(stderr, "bench_pingpong: needs 2 ranks (mpiexec -n 2 bench_pingpong)\n");
    MPI_Finalize();
    return 2;
  }
  const int large = 4 << 20;
  const double latency = one_way_seconds(rank, 8, 2000, 7);
  const double large_time = one_way_seconds(rank, large, 20, 7);
  if (rank == 0)
    std::printf("latency %.3g s, bandwidth %.4g B/s\n", latency, large / std::max(large_time - latency, 1e-12));
  MPI_Finalize();
  return 0;
}

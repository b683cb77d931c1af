#pragma once
/// \file tool_processes.h
/// The processes a tool runs as: one, or the K ranks of an `mpirun -n K` when the tools are built with MPI
/// (PCL_SPARSE_WITH_MPI; CMake finds it, and the build without it works alone). MPI is initialised only
/// when the tool was started by mpirun, so a plain run never pays for it. Not part of the library API.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    /// \brief The tool's processes: rank and count, and what the tiled encoder exchanges between them.
    class ProcessGroup
    {
    public:
      /// Joins the processes of an mpirun (MPI_Init), or stands alone (rank 0 of 1).
      ProcessGroup (int& argc, char**& argv);
      /// Leaves them (MPI_Finalize).
      ~ProcessGroup ();

      /// The tool's exit: \a code as is when alone or on success; on failure among several processes, every
      /// rank is stopped (MPI_Abort), since the others would otherwise wait for this one in their next
      /// exchange forever.
      int finish (int code) const;
      ProcessGroup (const ProcessGroup&) = delete;
      ProcessGroup& operator= (const ProcessGroup&) = delete;

      /// This process's rank, 0 .. size () - 1.
      int rank () const { return rank_; }
      /// Number of processes.
      int size () const { return size_; }
      /// Whether MPI was built in ("Open MPI 4.1" and the like), else "none".
      static std::string library ();

      /// Rank 0 receives every rank's bytes, in rank order (its own first); the others get an empty list.
      /// Every rank must call it.
      std::vector<std::vector<std::uint8_t>> gather (const std::vector<std::uint8_t>& mine) const;

      /// Every rank receives every rank's bytes, in rank order. Every rank must call it.
      std::vector<std::vector<std::uint8_t>> allGather (const std::vector<std::uint8_t>& mine) const;

      /// Every rank sends \a to_each[r] to rank r (one message a rank, itself included) and receives what every
      /// rank sent it, in rank order: an exchange between neighbours, with no rank in the middle. Every rank
      /// must call it.
      std::vector<std::vector<std::uint8_t>> exchange (std::vector<std::vector<std::uint8_t>> to_each) const;

    private:
      int rank_ = 0;
      int size_ = 1;
      bool initialised_ = false;
    };

    /// \brief Tiles shared out over \a ranks processes, balanced by points (largest first, each to the rank
    /// with the fewest points so far; ties to the lower rank): the tiles of rank \a rank, ascending.
    /// \param[in] points  core points per tile (tiles with none are left out)
    /// \param[in] ranks   number of processes
    /// \param[in] rank    this process
    std::vector<std::size_t>
    tilesOfRank (const std::vector<std::size_t>& points, int ranks, int rank);

    /// \brief The rank of every tile as tilesOfRank shares them out (-1 for tiles with no points).
    /// \param[in] points  core points per tile
    /// \param[in] ranks   number of processes
    std::vector<int>
    tileRanks (const std::vector<std::size_t>& points, int ranks);
  } // namespace tools
} // namespace pcl_sparse

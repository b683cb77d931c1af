#include "tool_processes.h"

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>

#ifdef PCL_SPARSE_WITH_MPI
#include <mpi.h>
#endif

namespace pcl_sparse
{
  namespace tools
  {
    namespace
    {
      /// Whether mpirun (Open MPI, MPICH, or a PMI launcher) started this process.
      bool
      startedByMpirun ()
      {
        for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
          if (std::getenv (name))
            return true;
        return false;
      }
    } // namespace

    ProcessGroup::ProcessGroup (int& argc, char**& argv)
    {
#ifdef PCL_SPARSE_WITH_MPI
      if (!startedByMpirun ())
        return;
      MPI_Init (&argc, &argv);
      initialised_ = true;
      MPI_Comm_rank (MPI_COMM_WORLD, &rank_);
      MPI_Comm_size (MPI_COMM_WORLD, &size_);
#else
      (void) argc;
      (void) argv;
      (void) startedByMpirun;
#endif
    }

    ProcessGroup::~ProcessGroup ()
    {
#ifdef PCL_SPARSE_WITH_MPI
      if (initialised_)
        MPI_Finalize ();
#endif
    }

    int
    ProcessGroup::finish (int code) const
    {
#ifdef PCL_SPARSE_WITH_MPI
      if (code != 0 && size_ > 1)
        MPI_Abort (MPI_COMM_WORLD, code);
#endif
      return code;
    }

    std::string
    ProcessGroup::library ()
    {
#ifdef PCL_SPARSE_WITH_MPI
      char version[MPI_MAX_LIBRARY_VERSION_STRING];
      int length = 0;
      MPI_Get_library_version (version, &length);
      std::string text (version, static_cast<std::size_t> (length));
      return text.substr (0, text.find_first_of (",\n"));
#else
      return "none";
#endif
    }

    std::vector<std::vector<std::uint8_t>>
    ProcessGroup::gather (const std::vector<std::uint8_t>& mine) const
    {
      std::vector<std::vector<std::uint8_t>> all;
      if (size_ == 1)
      {
        all.push_back (mine);
        return all;
      }
#ifdef PCL_SPARSE_WITH_MPI
      // Sizes first (as 64-bit counts), then the bytes, in pieces of at most 1 GiB (MPI counts are int).
      const unsigned long long my_size = mine.size ();
      std::vector<unsigned long long> sizes (static_cast<std::size_t> (size_));
      MPI_Gather (&my_size, 1, MPI_UNSIGNED_LONG_LONG, sizes.data (), 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
      constexpr std::size_t piece = std::size_t (1) << 30;
      if (rank_ != 0)
      {
        for (std::size_t at = 0; at < mine.size (); at += piece)
          MPI_Send (mine.data () + at, static_cast<int> (std::min (piece, mine.size () - at)), MPI_BYTE, 0, 0, MPI_COMM_WORLD);
        return all;
      }
      all.resize (static_cast<std::size_t> (size_));
      all[0] = mine;
      for (int r = 1; r < size_; ++r)
      {
        all[r].resize (sizes[r]);
        for (std::size_t at = 0; at < all[r].size (); at += piece)
          MPI_Recv (all[r].data () + at, static_cast<int> (std::min (piece, all[r].size () - at)), MPI_BYTE, r, 0,
                    MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
#endif
      return all;
    }

    std::vector<std::vector<std::uint8_t>>
    ProcessGroup::allGather (const std::vector<std::uint8_t>& mine) const
    {
      std::vector<std::vector<std::uint8_t>> all = gather (mine);
      if (size_ == 1)
        return all;
#ifdef PCL_SPARSE_WITH_MPI
      // Rank 0 broadcasts the sizes, then each rank's bytes in pieces of at most 1 GiB.
      std::vector<unsigned long long> sizes (static_cast<std::size_t> (size_));
      if (rank_ == 0)
        for (int r = 0; r < size_; ++r)
          sizes[r] = all[r].size ();
      MPI_Bcast (sizes.data (), size_, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
      all.resize (static_cast<std::size_t> (size_));
      constexpr std::size_t piece = std::size_t (1) << 30;
      for (int r = 0; r < size_; ++r)
      {
        all[r].resize (sizes[r]);
        for (std::size_t at = 0; at < all[r].size (); at += piece)
          MPI_Bcast (all[r].data () + at, static_cast<int> (std::min (piece, all[r].size () - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
      }
#endif
      return all;
    }

    std::vector<std::vector<std::uint8_t>>
    ProcessGroup::exchange (std::vector<std::vector<std::uint8_t>> to_each) const
    {
      std::vector<std::vector<std::uint8_t>> from_each (static_cast<std::size_t> (size_));
      if (to_each.size () != from_each.size ())
        throw Error ("ProcessGroup::exchange: " + std::to_string (to_each.size ()) + " messages for " + std::to_string (size_) + " ranks");
      from_each[rank_] = std::move (to_each[rank_]);
#ifdef PCL_SPARSE_WITH_MPI
      if (size_ == 1)
        return from_each;
      // Sizes first (as 64-bit counts), then the bytes, in pieces of at most 1 GiB (MPI counts are int); pieces
      // between two ranks arrive in the order sent.
      std::vector<unsigned long long> sizes (to_each.size ()), incoming (to_each.size ());
      for (std::size_t r = 0; r < to_each.size (); ++r)
        sizes[r] = to_each[r].size ();
      MPI_Alltoall (sizes.data (), 1, MPI_UNSIGNED_LONG_LONG, incoming.data (), 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
      constexpr std::size_t piece = std::size_t (1) << 30;
      std::vector<MPI_Request> requests;
      for (int r = 0; r < size_; ++r)
      {
        if (r == rank_)
          continue;
        from_each[r].resize (incoming[r]);
        for (std::size_t at = 0; at < from_each[r].size (); at += piece)
        {
          requests.emplace_back ();
          MPI_Irecv (from_each[r].data () + at, static_cast<int> (std::min (piece, from_each[r].size () - at)), MPI_BYTE, r, 1,
                     MPI_COMM_WORLD, &requests.back ());
        }
        for (std::size_t at = 0; at < to_each[r].size (); at += piece)
        {
          requests.emplace_back ();
          MPI_Isend (to_each[r].data () + at, static_cast<int> (std::min (piece, to_each[r].size () - at)), MPI_BYTE, r, 1,
                     MPI_COMM_WORLD, &requests.back ());
        }
      }
      MPI_Waitall (static_cast<int> (requests.size ()), requests.data (), MPI_STATUSES_IGNORE);
#endif
      return from_each;
    }

    std::vector<int>
    tileRanks (const std::vector<std::size_t>& points, int ranks)
    {
      std::vector<std::size_t> order;
      for (std::size_t t = 0; t < points.size (); ++t)
        if (points[t] > 0)
          order.push_back (t);
      std::stable_sort (order.begin (), order.end (), [&] (std::size_t a, std::size_t b) { return points[a] > points[b]; });
      std::vector<std::size_t> load (static_cast<std::size_t> (std::max (ranks, 1)), 0);
      std::vector<int> rank_of (points.size (), -1);
      for (std::size_t t : order)
      {
        const std::size_t r = static_cast<std::size_t> (std::min_element (load.begin (), load.end ()) - load.begin ());
        load[r] += points[t];
        rank_of[t] = static_cast<int> (r);
      }
      return rank_of;
    }

    std::vector<std::size_t>
    tilesOfRank (const std::vector<std::size_t>& points, int ranks, int rank)
    {
      const std::vector<int> rank_of = tileRanks (points, ranks);
      std::vector<std::size_t> mine;
      for (std::size_t t = 0; t < rank_of.size (); ++t)
        if (rank_of[t] == rank)
          mine.push_back (t);
      return mine;
    }
  } // namespace tools
} // namespace pcl_sparse

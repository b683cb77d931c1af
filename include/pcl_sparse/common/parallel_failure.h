#pragma once
/// \file parallel_failure.h
/// The first exception thrown in the bodies of an OpenMP loop, kept and thrown again after the loop: an
/// exception may not leave an OpenMP region (the program would end in std::terminate), and a caller's
/// progress callback that throws to cancel, or an allocation that fails, must reach the caller as an
/// exception it can catch.

#include <atomic>
#include <exception>
#include <mutex>

namespace pcl_sparse
{
  /// \brief Keeps the first exception of a parallel loop's bodies; the bodies after it are skipped.
  ///
  ///     ParallelFailure failure;
  ///     #pragma omp parallel for
  ///     for (long i = 0; i < n; ++i)
  ///       failure.run ([&] { work (i); });
  ///     failure.rethrow ();
  class ParallelFailure
  {
  public:
    /// Runs \a body unless a body has failed already; keeps the first exception it throws.
    template <typename Body>
    void
    run (Body&& body) noexcept
    {
      if (failed_.load (std::memory_order_relaxed))
        return;
      try
      {
        body ();
      }
      catch (...)
      {
        const std::lock_guard<std::mutex> lock (mutex_);
        if (!first_)
          first_ = std::current_exception ();
        failed_.store (true, std::memory_order_relaxed);
      }
    }

    /// Whether a body has failed (the loop's other work may stop early).
    bool failed () const { return failed_.load (std::memory_order_relaxed); }

    /// Throws the kept exception again, if a body failed.
    void
    rethrow () const
    {
      if (first_)
        std::rethrow_exception (first_);
    }

  private:
    std::atomic<bool> failed_{false};
    std::mutex mutex_;
    std::exception_ptr first_;
  };
} // namespace pcl_sparse

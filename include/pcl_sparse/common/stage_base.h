#pragma once
/// \file stage_base.h
/// \brief What every stage of the library shares: its class name, thread count, progress callback and the
/// way it refuses bad input.
///
/// Error policy of the whole library: a stage, loader or tool that cannot do its job throws
/// pcl_sparse::Error with a one-line message; a stage's message starts with "[ClassName::compute]" (or the
/// setter's name). No stage prints an error and returns an empty result instead. Points a stage cannot
/// process (a vertex without a face, for example) are not errors: they get NaN outputs and is_dense =
/// false, as in PCL.

#include <pcl_sparse/common/progress.h>

#include <string>

namespace pcl_sparse
{
  /// \brief Settings and helpers shared by every stage (PCL style: setters, then compute (output)).
  class StageBase
  {
  public:
    virtual ~StageBase () = default;

    /// \brief OpenMP threads for compute (0, the default, lets OpenMP decide). Outputs never depend on it.
    /// \param[in] threads number of threads in [0, 1024]
    /// \throws pcl_sparse::Error for a count outside [0, 1024] (100000 threads crashed the OpenMP runtime)
    void setNumberOfThreads (int threads);
    /// \brief The thread count set (0: OpenMP's default).
    int getNumberOfThreads () const { return num_threads_; }

    /// \brief Progress reports of compute: called with a stage name and the fraction done in [0, 1].
    /// \param[in] progress the callback; empty (the default) for none
    void setProgressCallback (const ProgressCallback& progress) { progress_ = progress; }

    /// \brief The stage's class name, as error messages name it.
    const std::string& getClassName () const { return name_; }

  protected:
    /// \param[in] name the class name, without namespace
    explicit StageBase (std::string name) : name_ (std::move (name)) {}

    /// \brief Throws pcl_sparse::Error ("[<class name>::compute] " + message).
    [[noreturn]] void fail (const std::string& message) const;

    /// \brief The thread count compute uses: the one set, or OpenMP's maximum when it is 0.
    int threadsToUse () const;

    /// \brief Reports \a fraction of \a stage done, when a progress callback is set.
    void reportProgress (const std::string& stage, double fraction) const
    {
      if (progress_)
        progress_ (stage, fraction);
    }

    int num_threads_ = 0;
    ProgressCallback progress_;
    std::string name_;
  };
} // namespace pcl_sparse

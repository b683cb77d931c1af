#pragma once
/// \file progress.h
/// Progress reporting for long stages: a callback the stages call, and a console printer for the tools.

#include <functional>
#include <string>

namespace pcl_sparse
{
  /// Called by long stages with the stage name and the fraction done in [0, 1]. May be empty.
  using ProgressCallback = std::function<void (const std::string& stage, double fraction)>;

  /// A ProgressCallback printing "stage: NN%" on stderr, at most once per percent, on one line per stage
  /// (carriage returns on a terminal).
  /// \param[in] quiet  print nothing
  /// \return the callback
  ProgressCallback
  makeConsoleProgress (bool quiet);
} // namespace pcl_sparse

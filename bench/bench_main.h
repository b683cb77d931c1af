#pragma once
/// \file bench_main.h
/// A benchmark's main: a missing or broken input file ends it with "program: message" and exit code 1
/// instead of std::terminate's abort.

#include <exception>
#include <iostream>

/// Returns \a run (argc, argv), or 1 after printing the message of what it threw.
template <typename Run>
int
runReportingErrors (int argc, char** argv, Run run)
{
  try
  {
    return run (argc, argv);
  }
  catch (const std::exception& e)
  {
    std::cerr << argv[0] << ": " << e.what () << "\n";
    return 1;
  }
}

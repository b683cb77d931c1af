#pragma once
/// \file error_message.h
/// The message of the pcl_sparse::Error a call throws: for tests that check a refusal says why, not only
/// that something was thrown.

#include <pcl_sparse/common/error.h>

#include <string>

namespace pcl_sparse_test
{
  /// Runs \a call and returns the message of the pcl_sparse::Error it throws, "" when it throws none (so a
  /// comparison with the expected message fails); any other exception goes on to fail the test.
  template <typename Call>
  std::string
  errorMessage (Call call)
  {
    try
    {
      call ();
    }
    catch (const pcl_sparse::Error& e)
    {
      return e.what ();
    }
    return "";
  }
} // namespace pcl_sparse_test

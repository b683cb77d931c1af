#pragma once
/// \file point_types.h
/// \brief The point types the compiled library instantiates its templated stages for.
///
/// Any other point type with x, y, z works too: define PCL_NO_PRECOMPILE before including a stage's
/// header, or include its impl/*.hpp, and the templates are compiled in your program (as in PCL).

#include <pcl/point_types.h>

/// \brief Calls \a MACRO once for every input point type the library is compiled for: PointXYZ,
/// PointXYZI, PointXYZRGB, PointXYZRGBA, PointNormal and PointXYZRGBNormal.
#define PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE(MACRO) \
  MACRO (pcl::PointXYZ)                               \
  MACRO (pcl::PointXYZI)                              \
  MACRO (pcl::PointXYZRGB)                            \
  MACRO (pcl::PointXYZRGBA)                           \
  MACRO (pcl::PointNormal)                            \
  MACRO (pcl::PointXYZRGBNormal)

/// \brief Calls \a MACRO once for every output point type of resampling the library is compiled for:
/// PointNormal, PointXYZ, PointXYZRGB, PointXYZRGBNormal and PointXYZINormal.
#define PCL_SPARSE_FOR_EACH_OUTPUT_POINT_TYPE(MACRO) \
  MACRO (pcl::PointNormal)                             \
  MACRO (pcl::PointXYZ)                                \
  MACRO (pcl::PointXYZRGB)                             \
  MACRO (pcl::PointXYZRGBNormal)                       \
  MACRO (pcl::PointXYZINormal)

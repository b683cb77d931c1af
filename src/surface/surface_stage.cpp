#include <pcl_sparse/surface/impl/surface_stage.hpp>

#define PCL_SPARSE_INSTANTIATE_SURFACE_STAGE(T) template class pcl_sparse::SurfaceStage<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_SURFACE_STAGE)

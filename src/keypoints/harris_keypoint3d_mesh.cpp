#include <pcl_sparse/keypoints/impl/harris_keypoint3d_mesh.hpp>

#define PCL_SPARSE_INSTANTIATE_HARRIS(T) template class pcl_sparse::HarrisKeypoint3DMesh<T>;
PCL_SPARSE_FOR_EACH_INPUT_POINT_TYPE (PCL_SPARSE_INSTANTIATE_HARRIS)

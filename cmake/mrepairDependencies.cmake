# Finds CGAL with its Eigen and TBB support targets. Shared by the build tree
# and the installed package config, so that both resolve the same way.
find_package(CGAL 5.5 REQUIRED)
find_package(Eigen3 3.3 REQUIRED)
include(CGAL_Eigen3_support)
find_package(Threads REQUIRED)
find_package(TBB REQUIRED)
include(CGAL_TBB_support)
if(NOT TARGET CGAL::TBB_support)
  message(FATAL_ERROR "mrepair: CGAL::TBB_support was not created (TBB not usable by CGAL)")
endif()

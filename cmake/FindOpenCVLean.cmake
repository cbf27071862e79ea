# Finds only the three OpenCV 4 modules the product uses (core, imgproc, imgcodecs) from Debian's
# split packages libopencv-{core,imgproc,imgcodecs}-dev. Debian's OpenCVConfig.cmake ships only in
# libopencv-dev, which drags in every module (dnn, video, highgui, Qt...): too heavy for 2 cores.
# Defines the imported targets OpenCV::core, OpenCV::imgproc, OpenCV::imgcodecs.
find_path(OpenCVLean_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
find_path(OpenCVLean_CONFIG_INCLUDE_DIR opencv2/cvconfig.h
          PATHS /usr/include/${CMAKE_LIBRARY_ARCHITECTURE} PATH_SUFFIXES opencv4)
set(_sas_cv_vars OpenCVLean_INCLUDE_DIR)
foreach(_module core imgproc imgcodecs)
  find_library(OpenCVLean_${_module}_LIBRARY opencv_${_module})
  list(APPEND _sas_cv_vars OpenCVLean_${_module}_LIBRARY)
endforeach()
if(OpenCVLean_INCLUDE_DIR AND EXISTS "${OpenCVLean_INCLUDE_DIR}/opencv2/core/version.hpp")
  file(STRINGS "${OpenCVLean_INCLUDE_DIR}/opencv2/core/version.hpp" _sas_cv_ver
       REGEX "#define CV_VERSION_(MAJOR|MINOR|REVISION) ")
  string(REGEX REPLACE ".*MAJOR +([0-9]+).*MINOR +([0-9]+).*REVISION +([0-9]+).*" "\\1.\\2.\\3"
         OpenCVLean_VERSION "${_sas_cv_ver}")
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenCVLean REQUIRED_VARS ${_sas_cv_vars}
                                  VERSION_VAR OpenCVLean_VERSION)
if(OpenCVLean_FOUND)
  set(_sas_cv_includes "${OpenCVLean_INCLUDE_DIR}")
  if(OpenCVLean_CONFIG_INCLUDE_DIR)
    list(APPEND _sas_cv_includes "${OpenCVLean_CONFIG_INCLUDE_DIR}")
  endif()
  foreach(_module core imgproc imgcodecs)
    if(NOT TARGET OpenCV::${_module})
      add_library(OpenCV::${_module} UNKNOWN IMPORTED)
      set_target_properties(OpenCV::${_module} PROPERTIES
        IMPORTED_LOCATION "${OpenCVLean_${_module}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${_sas_cv_includes}")
    endif()
  endforeach()
  set_property(TARGET OpenCV::imgproc APPEND PROPERTY INTERFACE_LINK_LIBRARIES OpenCV::core)
  set_property(TARGET OpenCV::imgcodecs APPEND PROPERTY INTERFACE_LINK_LIBRARIES OpenCV::imgproc)
endif()
mark_as_advanced(${_sas_cv_vars} OpenCVLean_CONFIG_INCLUDE_DIR)

# Imported targets opencv_<module> for the OpenCV modules tilejet uses.
# Debian ships OpenCVConfig.cmake only in the libopencv-dev meta package, which drags in every
# module (VTK, Qt and the rest); the per-module -dev packages are all tilejet needs.
function(tilejet_find_opencv)
    find_path(TILEJET_OPENCV_INCLUDE opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
    foreach(module IN LISTS ARGN)
        if(TARGET opencv_${module})
            continue()
        endif()
        find_library(TILEJET_OPENCV_${module} opencv_${module} REQUIRED)
        add_library(opencv_${module} SHARED IMPORTED GLOBAL)
        set_target_properties(opencv_${module} PROPERTIES
            IMPORTED_LOCATION ${TILEJET_OPENCV_${module}}
            INTERFACE_SYSTEM_INCLUDE_DIRECTORIES ${TILEJET_OPENCV_INCLUDE}
            INTERFACE_INCLUDE_DIRECTORIES ${TILEJET_OPENCV_INCLUDE})
    endforeach()
endfunction()

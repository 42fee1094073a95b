# The modules of src/: each folder src/NAME/ is one module, an OBJECT library im_NAME, which declares
# here, in one place, the modules it uses (USES) and the public headers of include/indentmap/ it owns
# (HEADERS; default NAME.h when there is one). The libraries and the program are built from the
# modules' objects. tests/module_graph.py (ctest module_graph) checks the code against these
# declarations: a symbol or a header of an undeclared module, a cycle, a declared module left unused.
# docs/architecture.md shows the graph (python3 tests/module_graph.py --layers BUILD/modules.json).
#
# Every module compiles with indentmap_dependencies: the external libraries and the public include
# paths of the library, which its users get too; src/ and the generated sources are the modules' own.

add_library(indentmap_dependencies INTERFACE)
target_include_directories(indentmap_dependencies INTERFACE
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>)

set(IM_MODULES "")
function(im_module name)
  cmake_parse_arguments(PARSE_ARGV 1 MODULE "" "" "USES;HEADERS")
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.c)
  if(NOT IM_GPU)
    list(FILTER sources EXCLUDE REGEX "/src/solver/[^/]*gpu[^/]*\\.c$")
  endif()
  if(NOT IM_MPI) # the scene's ensembles over MPI ranks
    list(FILTER sources EXCLUDE REGEX "/src/scene/ranks\\.c$")
  endif()
  if(NOT DEFINED MODULE_HEADERS AND EXISTS ${PROJECT_SOURCE_DIR}/include/indentmap/${name}.h)
    set(MODULE_HEADERS ${name}.h)
  endif()
  add_library(im_${name} OBJECT ${sources})
  set_target_properties(im_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_include_directories(im_${name} PRIVATE ${PROJECT_SOURCE_DIR}/src ${PROJECT_BINARY_DIR}/generated)
  target_link_libraries(im_${name} PUBLIC indentmap_dependencies)
  foreach(used ${MODULE_USES})
    target_link_libraries(im_${name} PUBLIC im_${used})
  endforeach()
  set_property(GLOBAL PROPERTY IM_MODULE_USES_${name} "${MODULE_USES}")
  set_property(GLOBAL PROPERTY IM_MODULE_HEADERS_${name} "${MODULE_HEADERS}")
  set_property(GLOBAL PROPERTY IM_MODULE_SOURCES_${name} "${sources}")
  set(IM_MODULES ${IM_MODULES} ${name} PARENT_SCOPE)
endfunction()

# A JSON array of strings from a CMake list (paths and names: nothing to escape).
function(im_json_strings out)
  set(items "")
  foreach(item ${ARGN})
    list(APPEND items "\"${item}\"")
  endforeach()
  list(JOIN items ", " joined)
  set(${out} "[${joined}]" PARENT_SCOPE)
endfunction()

# BUILD/modules.json: each module's declarations, sources and object files, for tests/module_graph.py.
function(im_module_graph_write)
  set(entries "")
  foreach(name ${IM_MODULES})
    foreach(what USES HEADERS SOURCES)
      get_property(values GLOBAL PROPERTY IM_MODULE_${what}_${name})
      im_json_strings(${what} ${values})
    endforeach()
    set(objects "[\"$<JOIN:$<TARGET_OBJECTS:im_${name}>,\"$<COMMA> \">\"]")
    list(APPEND entries "{\"name\": \"${name}\", \"uses\": ${USES}, \"headers\": ${HEADERS},\n   \"sources\": ${SOURCES},\n   \"objects\": ${objects}}")
  endforeach()
  list(JOIN entries ",\n  " joined)
  file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/modules.json
       CONTENT "{\"source_dir\": \"${PROJECT_SOURCE_DIR}\",\n \"modules\": [\n  ${joined}]}\n")
endfunction()

set(IM_GPU_MODULE "")
if(IM_GPU)
  set(IM_GPU_MODULE gpu)
endif()
set(IM_MPI_MODULE "")
if(IM_MPI)
  set(IM_MPI_MODULE mpi)
endif()

# Bottom up; a module uses only modules above it in this list.
im_module(core HEADERS field.h status.h version.h gpu_config.h mpi_config.h)
if(IM_GPU)
  im_module(gpu USES core)
endif()
im_module(io USES core)
im_module(colormap USES core)
im_module(indenter USES core)
im_module(theory USES core indenter)
im_module(surface USES core io theory)
im_module(formats USES core indenter io surface)
im_module(render USES colormap core indenter)
im_module(typeset USES core io render)
target_compile_definitions(im_typeset PRIVATE IM_FONT_DIR="${IM_FONT_DIR}")
im_module(figure USES colormap core io render typeset)
im_module(solver USES core ${IM_GPU_MODULE} indenter io)
im_module(measure USES core indenter io)
im_module(history USES core indenter io measure solver theory)
im_module(viewer USES core io)
im_module(plot USES colormap core figure io typeset)
im_module(paper USES colormap core figure io plot render surface theory)
if(IM_MPI)
  im_module(mpi USES core indenter io solver surface)
endif()
im_module(front HEADERS indent.h info.h USES colormap core figure formats ${IM_GPU_MODULE} history indenter io
          measure plot render solver surface theory viewer)
im_module(scene HEADERS scene.h scene_ranks.h USES colormap core figure formats front history indenter io measure
          ${IM_MPI_MODULE} paper plot render solver surface theory)
im_module(cli USES colormap core figure formats front history indenter io measure ${IM_MPI_MODULE} render
          scene solver surface theory)

set(IM_LIBRARY_MODULES ${IM_MODULES})
list(REMOVE_ITEM IM_LIBRARY_MODULES cli)
list(TRANSFORM IM_LIBRARY_MODULES PREPEND im_ OUTPUT_VARIABLE IM_LIBRARY_MODULE_TARGETS)
im_module_graph_write()

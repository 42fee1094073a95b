# Turns each shaders/NAME[.STAGE].glsl into `const char im_shader_NAME[_STAGE][]` (NUL-terminated) in one
# generated C file. Run as: cmake -DOUTPUT=file.c -DSHADER_DIR=dir -P embed_shaders.cmake
# The shaders must be ASCII (the bytes initialise a char array).
file(GLOB SOURCES ${SHADER_DIR}/*.glsl)
list(SORT SOURCES)
set(code "/* Generated from shaders/NAME.STAGE.glsl by shaders/embed_shaders.cmake: do not edit. */\n")
foreach(source ${SOURCES})
  get_filename_component(name ${source} NAME)
  string(REGEX REPLACE "\\.glsl$" "" name ${name})
  string(REGEX REPLACE "[^A-Za-z0-9]" "_" name ${name})
  file(READ ${source} hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND code "const char im_shader_${name}[] = {${bytes}0x00};\n")
endforeach()
file(WRITE ${OUTPUT}.new "${code}")
file(COPY_FILE ${OUTPUT}.new ${OUTPUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUTPUT}.new)

# Writes a patched copy of Debian 12's VkFFT header (libvkfft-dev 1.2.26) that compiles as C and
# compiles its shaders with glslang 12; /usr/include is never touched.
#   cmake -DINPUT=/usr/include/vkFFT.h -DOUTPUT=.../generated/vkfft/vkFFT.h -P cmake/patch_vkfft.cmake
# Every edit names the exact text it expects and how many times: a header that differs (another
# VkFFT version) stops the build with FATAL_ERROR instead of being half patched.
#
# (a) Three `VkCommandBuffer commandBuffer = {};` lines are C++ only: an empty initializer for a
#     handle (a pointer) is an error in C11. They become `= VK_NULL_HANDLE`.
# (b) Its two built-in glslang_resource_t tables are positional and predate glslang 12, which added
#     nine max_*_ext mesh fields before max_dual_source_draw_buffers_ext: every later value slides,
#     the `limits` block (while loops, non-inductive for loops, ...) ends up zero and every VkFFT
#     shader fails to parse at run time. The tables are removed and glslang's own default table
#     (glslang_default_resource(), library glslang-default-resource-limits) is passed instead: it
#     is built from the same glslang_resource_t the linked glslang was compiled with, so it cannot
#     go out of step again as inserting the missing fields by hand could.
# (c) It sizes its kernels' shared memory to the device's whole maxComputeSharedMemorySize, and then
#     declares a few variables more: on lavapipe (32 KiB) the double-precision kernels of sides that
#     are not powers of two used 32928 bytes, which the validation layers reject
#     (VUID-RuntimeSpirv-Workgroup-06530). It is told 1 KiB less than the device has, and its
#     power-of-two size follows (left at the device's, a 2048 x 1024 plan divided by zero).
# (d) In its multi-buffer mode (buffers beyond one storage buffer's range, the GPU engine's parts),
#     the forward R2C's multi-upload decomposition (VkFFTPlanR2CMultiUploadDecomposition, used when
#     the first axis takes several uploads: 16384 and longer in double) computes its input's block
#     count into outputBufferBlockNum: inputBufferBlockNum stays 0, becomes 1, and the kernel reads
#     the modes as one block of the first part's size. On an H200 a 16384^2 periodic solve (modes
#     2 GiB + 256 KiB: the last row in a second part) stopped after 980 iterations and a 32768^2
#     one (5 parts) at its first (docs/benchmarks.md, "GPU engine"). The two assignments name the
#     input's count.
cmake_minimum_required(VERSION 3.25)
if(NOT INPUT OR NOT OUTPUT)
  message(FATAL_ERROR "patch_vkfft.cmake: pass -DINPUT=vkFFT.h -DOUTPUT=patched/vkFFT.h")
endif()
file(READ "${INPUT}" text)

# count_of(VAR TEXT PATTERN): how many times PATTERN occurs in TEXT.
function(count_of var text pattern)
  string(LENGTH "${text}" full)
  string(REPLACE "${pattern}" "" rest "${text}")
  string(LENGTH "${rest}" left)
  string(LENGTH "${pattern}" one)
  math(EXPR n "(${full} - ${left}) / ${one}")
  set(${var} ${n} PARENT_SCOPE)
endfunction()

# replace_exactly(EXPECTED OLD NEW): replaces OLD by NEW in `text`, which must hold OLD EXPECTED times.
macro(replace_exactly expected old new)
  count_of(found "${text}" "${old}")
  if(NOT found EQUAL ${expected})
    message(FATAL_ERROR "patch_vkfft.cmake: ${INPUT}: expected ${expected} occurrence(s) of '${old}', "
                        "found ${found}: not the VkFFT 1.2.26 header this patch was written for")
  endif()
  string(REPLACE "${old}" "${new}" text "${text}")
endmacro()

# (a)
replace_exactly(3 "VkCommandBuffer commandBuffer = {};" "VkCommandBuffer commandBuffer = VK_NULL_HANDLE;")

# (b) Each table runs from its declaration to the first "} };" after it (the close of `limits`
# and of the table), and is used once, as the input's resource.
set(table_start "const glslang_resource_t default_resource = {")
set(table_end "/* .generalConstantMatrixVectorIndexing = */ 1,")
count_of(tables "${text}" "${table_start}")
count_of(ends "${text}" "${table_end}")
if(NOT tables EQUAL 2 OR NOT ends EQUAL 2)
  message(FATAL_ERROR "patch_vkfft.cmake: ${INPUT}: expected 2 glslang resource tables ending in "
                      "'${table_end}', found ${tables} and ${ends}")
endif()
foreach(k 1 2)
  string(FIND "${text}" "${table_start}" begin)
  string(SUBSTRING "${text}" ${begin} -1 tail)
  string(FIND "${tail}" "${table_end}" end_in_tail)
  string(SUBSTRING "${tail}" ${end_in_tail} -1 after_end)
  string(FIND "${after_end}" "} };" close)
  if(close EQUAL -1 OR close GREATER 100)
    message(FATAL_ERROR "patch_vkfft.cmake: ${INPUT}: glslang resource table ${k} does not close with '} };'")
  endif()
  math(EXPR cut "${end_in_tail} + ${close} + 4")
  string(SUBSTRING "${text}" 0 ${begin} head)
  string(SUBSTRING "${tail}" ${cut} -1 rest)
  set(text "${head}/* indentmap: pre-glslang-12 resource table removed; glslang_default_resource() below */${rest}")
endforeach()
replace_exactly(2 "&default_resource," "glslang_default_resource(),")
replace_exactly(1 "#include <glslang/Include/glslang_c_interface.h>"
  "#include <glslang/Include/glslang_c_interface.h>\n#include <glslang/Public/resource_limits_c.h> /* indentmap */")

# (c)
replace_exactly(1 "app->configuration.sharedMemorySize = physicalDeviceProperties.limits.maxComputeSharedMemorySize;"
  "app->configuration.sharedMemorySize = physicalDeviceProperties.limits.maxComputeSharedMemorySize - 1024; /* indentmap */")
replace_exactly(1 "app->configuration.sharedMemorySizePow2 = (uint64_t)pow(2, (uint64_t)log2(physicalDeviceProperties.limits.maxComputeSharedMemorySize));"
  "app->configuration.sharedMemorySizePow2 = (uint64_t)pow(2, (uint64_t)log2(app->configuration.sharedMemorySize)); /* indentmap */")

# (d)
replace_exactly(2 "axis->specializationConstants.outputBufferBlockNum = (locBufferNum == 1) ? 1 : (uint64_t)ceil(totalSize / (double)(axis->specializationConstants.inputBufferBlockSize * storageComplexSize));"
  "axis->specializationConstants.inputBufferBlockNum = (locBufferNum == 1) ? 1 : (uint64_t)ceil(totalSize / (double)(axis->specializationConstants.inputBufferBlockSize * storageComplexSize)); /* indentmap */")

get_filename_component(dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${dir}")
file(WRITE "${OUTPUT}.tmp" "/* Generated by indentmap's cmake/patch_vkfft.cmake from ${INPUT}; do not edit. */\n${text}")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")

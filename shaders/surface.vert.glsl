#version 330 core
// The deformed surface as a mesh generated from gl_VertexID: six vertices (two triangles) per
// mesh cell, cells row by row. Corner (a, b) lies at (min(a * stride, nx), min(b * stride, ny)) in
// patches, at the height (in patches) stored for it in `corners`.
uniform sampler2D corners;     // (cells.x + 1) x (cells.y + 1), R32F, heights / delta
uniform ivec2 cells;           // mesh cells along x and y
uniform ivec2 grid;            // patches nx, ny
uniform int stride;            // patches per mesh cell
uniform float exaggeration;
uniform mat4 view_projection;
out vec3 world;

// The split of a cell: (0,0)-(1,0)-(1,1) and (0,0)-(1,1)-(0,1), along the diagonal (0,0)-(1,1).
const ivec2 CORNER[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

void main()
{
    int cell = gl_VertexID / 6;
    ivec2 corner = ivec2(cell % cells.x, cell / cells.x) + CORNER[gl_VertexID % 6];
    vec2 xy = vec2(min(corner * stride, grid));
    world = vec3(xy, exaggeration * texelFetch(corners, corner, 0).r);
    gl_Position = view_projection * vec4(world, 1.0);
}

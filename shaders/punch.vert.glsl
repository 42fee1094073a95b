// The punch: a polyline profile (r, z) in world units revolved around the vertical axis, six
// vertices per quad between two profile points and two of `segments` angles. Normals are smooth
// around the axis and constant along each profile segment (exact for a cone).
const int MAX_PROFILE = 64;
uniform vec2 profile[MAX_PROFILE];
uniform int segments;
uniform vec2 axis;             // in patches
uniform mat4 view_projection;
out vec3 world;
out vec3 normal;

const ivec2 CORNER[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

void main()
{
    int quad = gl_VertexID / 6, ring = quad / segments;
    ivec2 corner = ivec2(quad % segments, ring) + CORNER[gl_VertexID % 6];
    float angle = 6.283185307179586 * float(corner.x) / float(segments);
    vec2 around = vec2(cos(angle), sin(angle));
    vec2 along = profile[ring + 1] - profile[ring];
    normal = normalize(vec3(along.y * around, -along.x));
    world = vec3(axis + profile[corner.y].x * around, profile[corner.y].y);
    gl_Position = view_projection * vec4(world, 1.0);
}

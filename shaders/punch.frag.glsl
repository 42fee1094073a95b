// The punch: diffuse plus a specular highlight, the normal turned towards the eye; optionally its
// half towards the camera cut away.
uniform vec3 punch_colour, light, eye;
uniform vec2 axis;
uniform vec2 towards_camera;   // horizontal unit vector from the axis towards the camera
uniform int cutaway;
uniform float opacity;
in vec3 world;
in vec3 normal;
out vec4 colour;

void main()
{
    if (cutaway != 0 && dot(world.xy - axis, towards_camera) > 0.0)
        discard;
    vec3 n = normalize(normal);
    vec3 view = normalize(eye - world);
    if (dot(n, view) < 0.0)
        n = -n;
    float diffuse = max(dot(n, light), 0.0);
    float specular = pow(max(dot(reflect(-light, n), view), 0.0), 40.0);
    vec3 c = punch_colour * (0.45 + 0.55 * diffuse) + vec3(0.3 * specular);
    colour = vec4(clamp(c, 0.0, 1.0), opacity);
}

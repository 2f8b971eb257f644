"""Writes the camera paths of this folder (README.md says what each is)."""
import json, math, os

def sub(a, b): return [a[i] - b[i] for i in range(3)]
def add(a, b): return [a[i] + b[i] for i in range(3)]
def mul(a, s): return [x * s for x in a]
def norm(a): return math.sqrt(sum(x * x for x in a))
def unit(a): return mul(a, 1.0 / norm(a))
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]

def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    z = mul(unit(sub(target, eye)), -1.0)
    x = unit(cross(list(up), z))
    y = cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        w, qx, qy, qz = 0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        w, qx, qy, qz = (m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        w, qx, qy, qz = (m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        w, qx, qy, qz = (m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s
    n = math.sqrt(w*w + qx*qx + qy*qy + qz*qz)
    if w < 0: n = -n
    return [w / n, qx / n, qy / n, qz / n]

def r(v): return round(v, 6) + 0.0

def camera(eye, q, fov, focus):
    return {"position": {"x": r(eye[0]), "y": r(eye[1]), "z": r(eye[2])},
            "orientation": {"w": r(q[0]), "x": r(q[1]), "y": r(q[2]), "z": r(q[3])},
            "vertical_fov": fov, "focus_distance": r(focus)}

def write(name, frames):
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), name), "w") as f:
        f.write('{"frames": [\n')
        f.write(",\n".join("  " + json.dumps(e) for e in frames))
        f.write("\n]}\n")

frame_count = 120
eye0, target0 = [-2.0, 1.2, 4.0], [-2.0, 0.1, -1.0]
d = unit(sub(target0, eye0))
q = look_at(eye0, target0)
write("foliage_forward.json", [{"animation_frame": i,
      "camera": camera(add(eye0, mul(d, 0.15 * i)), q, 0.8, norm(sub(target0, eye0)) - 0.15 * i)} for i in range(8)])

# carousel, panning 0.5 m per frame (20x its default animation's pan) while aiming at the ring,
# so that an open shutter blurs by a few pixels at 64 x 64.
target = [0.0, 1.0, -1.0]
frames = []
for i in range(8):
    eye = [-2.0 + 0.5 * i, 1.6, 6.0]
    frames.append({"animation_frame": i, "camera": camera(eye, look_at(eye, target), 0.8, norm(sub(target, eye)))})
write("carousel_fast_pan.json", frames)

# carousel's default animation split into its two motions (8 frames): the ring turns under the
# camera of frame 0, or the camera pans (eye from (-1.5, 1.6, 6), 3 m over 119 frames, aiming at
# (0, 1, -1)) over the ring of frame 0.
def carousel_camera(i):
    eye = [-1.5 + 3.0 * i / 119.0, 1.6, 6.0]
    return camera(eye, look_at(eye, target), 0.8, norm(sub(target, eye)))
write("carousel_objects_only.json", [{"animation_frame": i, "camera": carousel_camera(0)} for i in range(8)])
write("carousel_camera_only.json", [{"animation_frame": 0, "camera": carousel_camera(i)} for i in range(8)])

# The same two motions over 16 frames, for the confidence cap's history length (docs/BENCHMARKS.md,
# "Why a longer history costs error under motion").
write("carousel_objects_only_16.json", [{"animation_frame": i, "camera": carousel_camera(0)} for i in range(16)])
write("carousel_camera_only_16.json", [{"animation_frame": 0, "camera": carousel_camera(i)} for i in range(16)])

# The ring's motion alone over 80 frames, under the camera at the pan's midpoint (eye (0, 1.6, 6)):
# the ML paper's Carousel, where only objects move (docs/BENCHMARKS.md, "Multi-layer reservoir splatting").
write("carousel_objects_only_80.json", [{"animation_frame": i, "camera": carousel_camera(59.5)} for i in range(80)])

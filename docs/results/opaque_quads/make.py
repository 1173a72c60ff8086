# The opaque-quads check (docs/results/opaque_quads.md): six unlit quads at shuffled depths, one
# OPAQUE in the middle of the stack; writes quads.gltf, cam.json and quads.json. `python3 make.py SEED [--all-blend]`.
# Six unlit quads at shuffled depths, one OPAQUE in the middle of the stack; glTF + camera json;
# and the exact composite by ray casting (independent of the project).
import json, struct, base64, math, random, sys
random.seed(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
# --all-blend: the opaque quad as BLEND with alpha 1, what the methods drew before they took opaque geometry.
all_blend = '--all-blend' in sys.argv
quads = []
zs = [0.5, 0.3, 0.1, -0.1, -0.3, -0.5]
random.shuffle(zs)
opaque_z = sorted(zs)[2]  # third from the back: three layers in front of it
for i, z in enumerate(zs):
    cx, cy = random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3)
    hw, hh = random.uniform(0.35, 0.6), random.uniform(0.35, 0.6)
    col = [random.uniform(0.1, 0.95) for _ in range(3)]
    a = 1.0 if z == opaque_z else random.uniform(0.25, 0.75)
    quads.append(dict(c=(cx, cy), h=(hw, hh), z=z, col=col, a=a, opaque=(z == opaque_z)))
pos = []; idx = []
for i, q in enumerate(quads):
    (cx, cy), (hw, hh), z = q['c'], q['h'], q['z']
    pos += [cx-hw, cy-hh, z, cx+hw, cy-hh, z, cx+hw, cy+hh, z, cx-hw, cy+hh, z]
buf = b''.join(struct.pack('<f', v) for v in pos)
ibuf = b''.join(struct.pack('<H', v) for v in [0,1,2,0,2,3])
data = buf + ibuf
gl = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_unlit"],
      "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(buf)}, {"buffer": 0, "byteOffset": len(buf), "byteLength": 12}],
      "accessors": [], "meshes": [], "materials": [], "nodes": [], "scenes": [{"nodes": list(range(6))}], "scene": 0}
gl["accessors"].append({"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"})
for i, q in enumerate(quads):
    lo = [min(pos[i*12+k*3+d] for k in range(4)) for d in range(3)]
    hi = [max(pos[i*12+k*3+d] for k in range(4)) for d in range(3)]
    gl["accessors"].append({"bufferView": 0, "byteOffset": i*48, "componentType": 5126, "count": 4, "type": "VEC3", "min": lo, "max": hi})
    m = {"pbrMetallicRoughness": {"baseColorFactor": q['col'] + [q['a']]}, "extensions": {"KHR_materials_unlit": {}}, "doubleSided": True,
         "alphaMode": "OPAQUE" if q['opaque'] and not all_blend else "BLEND"}
    gl["materials"].append(m)
    gl["meshes"].append({"primitives": [{"attributes": {"POSITION": i+1}, "indices": 0, "material": i}]})
    gl["nodes"].append({"mesh": i})
json.dump(gl, open('quads.gltf', 'w'))
eye = [0.35, 0.25, 3.2]
json.dump({"position": eye, "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 45, "near": 0.5, "far": 10}, open('cam.json', 'w'))
json.dump(quads, open('quads.json', 'w'))

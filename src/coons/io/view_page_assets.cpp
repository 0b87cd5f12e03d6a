// The script and style of the `coons view` page (view_page.h). The script reads the embedded
// JSON (#coons-data), draws with three.js (global THREE, revision 111 or later) and SVG.
#include "view_page.h"

namespace coons {

namespace {

constexpr std::string_view kStyle = R"CSS(
body { margin: 0; font: 14px/1.4 sans-serif; color: #222; background: #fafafa; }
header { padding: 6px 14px; border-bottom: 1px solid #ddd; background: #fff; }
header h1 { font-size: 18px; margin: 0; display: inline-block; }
header p { margin: 0 0 0 12px; display: inline-block; color: #555; }
main { display: flex; flex-wrap: wrap; gap: 12px; padding: 12px; }
#view3d { position: relative; flex: 1 1 560px; min-width: 320px; height: 560px; background: #fff;
          border: 1px solid #ddd; }
#surface { width: 100%; height: 100%; display: block; cursor: grab; }
.hint { position: absolute; right: 8px; bottom: 4px; color: #999; font-size: 12px; }
#side { flex: 0 1 540px; min-width: 320px; }
.slider { margin: 4px 0 10px 0; }
.slider label { display: block; font-weight: bold; }
.slider input { width: 100%; }
.slider output { font-family: monospace; }
#curves { width: 100%; background: #fff; border: 1px solid #ddd; }
#legend { font-size: 13px; margin-top: 6px; }
#legend span.swatch { display: inline-block; width: 18px; height: 3px; vertical-align: middle; margin-right: 4px; }
footer { padding: 4px 14px; color: #777; font-size: 12px; }
)CSS";

constexpr std::string_view kScript = R"JS(
(function () {
  'use strict';
  var body = document.body;
  function record(message) {
    if (!body.hasAttribute('data-error')) body.setAttribute('data-error', String(message));
  }
  var consoleError = console.error;
  console.error = function () {
    record(Array.prototype.join.call(arguments, ' '));
    return consoleError.apply(console, arguments);
  };
  var data = JSON.parse(document.getElementById('coons-data').textContent);
  var sliders = data.sliders;
  // every coordinate on the page is an offset from data.origin (exactly, shortest round trip):
  // drawn as it is, the origin added back for the test hook's net()
  var origin = data.origin || [0, 0, 0];
  var colours = ['#c0392b', '#2471a3', '#1e8449', '#7d3c98', '#b9770e', '#17202a'];
  var active = 0;
  // current[si]: the frame shown, an index into frames, or -1 for extra[si] (a value between the
  // frames that the page solved itself, see solvedFrame)
  var current = sliders.map(function (s) { return nearest(s, s.initial); });
  var extra = sliders.map(function () { return null; });

  function nearest(s, value) {
    var best = 0;
    for (var k = 1; k < s.frames.length; ++k)
      if (Math.abs(s.frames[k].parameter - value) < Math.abs(s.frames[best].parameter - value)) best = k;
    return best;
  }
  function frameAt(si) { return current[si] < 0 ? extra[si] : sliders[si].frames[current[si]]; }

  // --- a value between the frames (ViewSlider::ring): the one-ring α family solved here ---------
  // The interior system (I − β E − α D) x = (the ring's terms) of the mask b_ij = α·(diagonal
  // neighbours) + β·(edge neighbours), β = 1/4 − α, is diagonal in the sine basis:
  // x = S_i ((S_i R S_j) ./ λ) S_j with λ_pq = 1 − β(c_p + c_q) − α c_p c_q, c_p = 2 cos(π p/(k+1)).
  function sineMatrix(k) {  // the orthonormal DST-I, symmetric
    var S = new Float64Array(k * k), f = Math.sqrt(2 / (k + 1));
    for (var p = 0; p < k; ++p)
      for (var q = 0; q < k; ++q) S[p * k + q] = f * Math.sin(Math.PI * (p + 1) * (q + 1) / (k + 1));
    return S;
  }
  function multiply(A, B, C, rows, inner, cols) {  // C = A B (row-major)
    for (var i = 0; i < rows; ++i)
      for (var j = 0; j < cols; ++j) {
        var sum = 0;
        for (var k = 0; k < inner; ++k) sum += A[i * inner + k] * B[k * cols + j];
        C[i * cols + j] = sum;
      }
  }
  function ringNet(ring, alpha) {
    var m = ring.m, n = ring.n, r = m - 1, c = n - 1, beta = 0.25 - alpha, N = n + 1;
    var net = Float64Array.from(ring.net), Si = sineMatrix(r), Sj = sineMatrix(c);
    var R = new Float64Array(r * c), T = new Float64Array(r * c), cp = [], cq = [];
    for (var p = 0; p < r; ++p) cp.push(2 * Math.cos(Math.PI * (p + 1) / (r + 1)));
    for (var q = 0; q < c; ++q) cq.push(2 * Math.cos(Math.PI * (q + 1) / (c + 1)));
    function onRing(i, j) { return i === 0 || j === 0 || i === m || j === n; }
    for (var d = 0; d < 3; ++d) {
      for (var i = 1; i < m; ++i)
        for (var j = 1; j < n; ++j) {
          var sum = 0;
          for (var di = -1; di <= 1; ++di)
            for (var dj = -1; dj <= 1; ++dj)
              if ((di || dj) && onRing(i + di, j + dj))
                sum += (di && dj ? alpha : beta) * net[3 * ((i + di) * N + j + dj) + d];
          R[(i - 1) * c + j - 1] = sum;
        }
      multiply(Si, R, T, r, r, c);
      multiply(T, Sj, R, r, c, c);
      for (p = 0; p < r; ++p)
        for (q = 0; q < c; ++q) R[p * c + q] /= 1 - beta * (cp[p] + cq[q]) - alpha * cp[p] * cq[q];
      multiply(Si, R, T, r, r, c);
      multiply(T, Sj, R, r, c, c);
      for (i = 1; i < m; ++i)
        for (j = 1; j < n; ++j) net[3 * (i * N + j) + d] = R[(i - 1) * c + j - 1];
    }
    return net;
  }
  function basis(degree, t) {  // the Bernstein polynomials of `degree` at t
    var b = [], binomial = 1;
    for (var k = 0; k <= degree; ++k) {
      b.push(binomial * Math.pow(t, k) * Math.pow(1 - t, degree - k));
      binomial = binomial * (degree - k) / (k + 1);
    }
    return b;
  }
  function bernstein(degree, t) {  // the basis and its derivative at t: degree·(B_{k−1} − B_k) of degree − 1
    var b = basis(degree, t), lower = degree > 0 ? basis(degree - 1, t) : [], db = [];
    for (var k = 0; k <= degree; ++k) db.push(degree * ((k > 0 ? lower[k - 1] : 0) - (k < degree ? lower[k] : 0)));
    return [b, db];
  }
  // the unit normal of du × dv, as unit_cross (net/surface_point.h): 0 where it degenerates
  function unitCross(du, dv, normals, row) {
    var lu = Math.hypot(du[0], du[1], du[2]), lv = Math.hypot(dv[0], dv[1], dv[2]);
    if (!(lu > 0) || !(lv > 0)) return;
    var a = [du[0] / lu, du[1] / lu, du[2] / lu], b = [dv[0] / lv, dv[1] / lv, dv[2] / lv];
    var n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    var length = Math.hypot(n[0], n[1], n[2]);
    if (!(length > 1e-14)) return;
    for (var d = 0; d < 3; ++d) normals[row + d] = n[d] / length;
  }
  // the Bézier surface of the net on k × k samples (u = a/(k−1) along i, v = b/(k−1) along j),
  // with unit normals du × dv (0 where it degenerates), in the order of the precomputed frames
  function sampleNet(net, m, n, k) {
    var points = new Float64Array(3 * k * k), normals = new Float64Array(3 * k * k), N = n + 1;
    var along = [];
    for (var b = 0; b < k; ++b) along.push(bernstein(n, b / (k - 1)));
    for (var a = 0; a < k; ++a) {
      var bu = bernstein(m, a / (k - 1));
      for (b = 0; b < k; ++b) {
        var bv = along[b], p = [0, 0, 0], du = [0, 0, 0], dv = [0, 0, 0];
        for (var i = 0; i <= m; ++i)
          for (var j = 0; j <= n; ++j)
            for (var d = 0; d < 3; ++d) {
              var x = net[3 * (i * N + j) + d];
              p[d] += bu[0][i] * bv[0][j] * x;
              du[d] += bu[1][i] * bv[0][j] * x;
              dv[d] += bu[0][i] * bv[1][j] * x;
            }
        var row = 3 * (a * k + b);
        for (d = 0; d < 3; ++d) points[row + d] = p[d];
        unitCross(du, dv, normals, row);
      }
    }
    return [points, normals];
  }
  function solvedFrame(s, alpha) {
    var net = ringNet(s.ring, alpha), k = Math.round(Math.sqrt(s.frames[0].points.length / 3));
    var sampled = sampleNet(net, s.ring.m, s.ring.n, k);
    var frame = { parameter: alpha, ok: true, net: net, points: sampled[0], normals: sampled[1] };
    if (s.ring.m === s.ring.n && alpha >= -0.25 && alpha < 0)  // mu_from_alpha
      frame.mu = -s.ring.n * s.ring.n * (1 + 4 * alpha) / (4 * alpha);
    return frame;
  }

  // --- a value between the frames (ViewSlider::system): (A0 + t A1) x = B0 + t B1 solved here --
  // by LU with partial pivoting (at most ViewSystem::kMaxFree unknowns), in the page's coordinates:
  // A (x − o) = B − (A·1) o. null where a pivot vanishes or the net is not finite.
  function systemNet(sys, t) {
    var k = sys.free.length, M = new Float64Array(k * k), R = new Float64Array(3 * k), r, c, d, p;
    function add(triples, scale) {
      for (var e = 0; e < triples.length; e += 3) M[triples[e] * k + triples[e + 1]] += scale * triples[e + 2];
    }
    add(sys.A0, 1);
    add(sys.A1, t);
    for (r = 0; r < k; ++r) {
      var rowSum = 0;
      for (c = 0; c < k; ++c) rowSum += M[r * k + c];
      for (d = 0; d < 3; ++d) R[3 * r + d] = sys.B0[3 * r + d] + t * sys.B1[3 * r + d] - rowSum * origin[d];
    }
    for (p = 0; p < k; ++p) {
      var best = p;
      for (r = p + 1; r < k; ++r) if (Math.abs(M[r * k + p]) > Math.abs(M[best * k + p])) best = r;
      if (!(Math.abs(M[best * k + p]) > 0)) return null;
      if (best !== p) {
        for (c = 0; c < k; ++c) { var x = M[p * k + c]; M[p * k + c] = M[best * k + c]; M[best * k + c] = x; }
        for (d = 0; d < 3; ++d) { var y = R[3 * p + d]; R[3 * p + d] = R[3 * best + d]; R[3 * best + d] = y; }
      }
      for (r = p + 1; r < k; ++r) {
        var f = M[r * k + p] / M[p * k + p];
        if (f === 0) continue;
        for (c = p + 1; c < k; ++c) M[r * k + c] -= f * M[p * k + c];
        for (d = 0; d < 3; ++d) R[3 * r + d] -= f * R[3 * p + d];
      }
    }
    for (p = k - 1; p >= 0; --p)
      for (d = 0; d < 3; ++d) {
        var sum = R[3 * p + d];
        for (c = p + 1; c < k; ++c) sum -= M[p * k + c] * R[3 * c + d];
        R[3 * p + d] = sum / M[p * k + p];
      }
    var net = Float64Array.from(sys.net);
    for (r = 0; r < k; ++r)
      for (d = 0; d < 3; ++d) {
        if (!isFinite(R[3 * r + d])) return null;
        net[3 * sys.free[r] + d] = R[3 * r + d];
      }
    return net;
  }
  // the triangular Bézier surface of degree n at the samples of tri::sample_tri_surface: row
  // net_index(k − 1, s, r) at (u, v, w) = ((k − 1 − r − s), s, r) / (k − 1), by de Casteljau down
  // to degree 1; D_(1,0,−1) and D_(0,1,−1) from its three points
  function triSample(net, n, k) {
    function index(degree, j, c) { return c * (degree + 1) - c * (c - 1) / 2 + j; }
    var size = k * (k + 1) / 2, points = new Float64Array(3 * size), normals = new Float64Array(3 * size);
    var from = new Float64Array(net.length), to = new Float64Array(net.length);
    for (var r = 0; r < k; ++r)
      for (var s = 0; s + r < k; ++s) {
        var u = (k - 1 - r - s) / (k - 1), v = s / (k - 1), w = r / (k - 1), level = net, d;
        for (var degree = n; degree > 1; --degree) {
          for (var c = 0; c < degree; ++c)
            for (var j = 0; j + c < degree; ++j) {
              var o = 3 * index(degree - 1, j, c), a = 3 * index(degree, j, c), b = 3 * index(degree, j + 1, c),
                  e = 3 * index(degree, j, c + 1);
              for (d = 0; d < 3; ++d) to[o + d] = u * level[a + d] + v * level[b + d] + w * level[e + d];
            }
          level = to; to = from; from = level;
        }
        var row = 3 * index(k - 1, s, r), du = [], dv = [];
        for (d = 0; d < 3; ++d) {
          points[row + d] = u * level[d] + v * level[3 + d] + w * level[6 + d];
          du.push(n * (level[d] - level[6 + d]));
          dv.push(n * (level[3 + d] - level[6 + d]));
        }
        unitCross(du, dv, normals, row);
      }
    return [points, normals];
  }
  // Σ basis_u(a, i) basis_v(b, j) net(i, j) and its derivatives (a B-spline surface's samples)
  function tensorSample(net, sys) {
    var k = sys.samples, cu = sys.count_u, cv = sys.count_v;
    var points = new Float64Array(3 * k * k), normals = new Float64Array(3 * k * k);
    for (var a = 0; a < k; ++a)
      for (var b = 0; b < k; ++b) {
        var p = [0, 0, 0], du = [0, 0, 0], dv = [0, 0, 0], d;
        for (var i = 0; i < cu; ++i) {
          var nu = sys.basis_u[a * cu + i], dnu = sys.dbasis_u[a * cu + i];
          if (nu === 0 && dnu === 0) continue;
          for (var j = 0; j < cv; ++j) {
            var nv = sys.basis_v[b * cv + j], dnv = sys.dbasis_v[b * cv + j];
            for (d = 0; d < 3; ++d) {
              var x = net[3 * (i * cv + j) + d];
              p[d] += nu * nv * x;
              du[d] += dnu * nv * x;
              dv[d] += nu * dnv * x;
            }
          }
        }
        var row = 3 * (a * k + b);
        for (d = 0; d < 3; ++d) points[row + d] = p[d];
        unitCross(du, dv, normals, row);
      }
    return [points, normals];
  }
  function systemFrame(s, t) {
    var sys = s.system, net = systemNet(sys, t), sampled;
    if (!net) {
      var empty = new Float64Array(s.frames[0].points.length);
      return { parameter: t, ok: false, net: Float64Array.from(sys.net), points: empty, normals: empty };
    }
    if (sys.sampler === 'triangle') sampled = triSample(net, sys.n, sys.samples);
    else if (sys.sampler === 'tensor') sampled = tensorSample(net, sys);
    else sampled = sampleNet(net, sys.m, sys.n, sys.samples);
    return { parameter: t, ok: true, net: net, points: sampled[0], normals: sampled[1] };
  }

  // the frame index that shows `value`: a frame, or (-1) the value solved here when it lies
  // between the frames of a slider that can solve it (its ring or its system)
  function locate(si, value) {
    var s = sliders[si], k = nearest(s, value);
    // (only the frame of the value itself: 0.1 within 1e-12 of the frame 0.09999999999999998 showed
    // data-alpha 0.09999999999999998, where #alpha=0.1 is to show α = 0.1)
    if (!(s.ring || s.system) || !(value >= s.lower && value <= s.upper) || s.frames[k].parameter === value) return k;
    extra[si] = s.ring ? solvedFrame(s, value) : systemFrame(s, value);
    return -1;
  }
  function symbol(s) { return s.symbol || s.parameter; }
  function tick(x) { return String(Number(Number(x).toPrecision(3))); }
  function fmt(x) { return x === null || x === undefined ? '–' : Number(x).toPrecision(5); }

  // --- 3D: the surface with reflection lines, the net --------------------------------------
  var three = null;
  function setup3d() {
    var canvas = document.getElementById('surface');
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xffffff, 1);
    var scene = new THREE.Scene();
    var camera = new THREE.PerspectiveCamera(30, 1, 0.001, 1000);
    var turn = new THREE.Group();   // the user's rotation
    var upright = new THREE.Group();  // coons' z up is three's y up
    upright.rotation.x = -Math.PI / 2;
    turn.add(upright);
    scene.add(turn);
    // bounds over the frames of every slider, so that the view does not jump when a slider
    // moves; a frame wider along an axis than 4 times the median width there of its slider's
    // frames plus a quarter of their median size (the net of a nearly singular system at the end
    // of a range: 8 times the others' height on bspline_wave) is left out of them, or every other
    // frame would be drawn small, unless it is a frame the page opens on
    function boxOf(f) {
      var b = { lo: [Infinity, Infinity, Infinity], hi: [-Infinity, -Infinity, -Infinity] };
      [f.net, f.points].forEach(function (a) {
        for (var i = 0; i < a.length; ++i) {
          b.lo[i % 3] = Math.min(b.lo[i % 3], a[i]);
          b.hi[i % 3] = Math.max(b.hi[i % 3], a[i]);
        }
      });
      b.width = [0, 1, 2].map(function (c) { return b.hi[c] - b.lo[c]; });
      return b;
    }
    function median(values) {
      var sorted = values.slice().sort(function (a, b) { return a - b; });
      return sorted.length ? sorted[Math.floor(sorted.length / 2)] : 0;
    }
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    function include(b) {
      if (!b.width.every(isFinite)) return;
      for (var c = 0; c < 3; ++c) {
        lo[c] = Math.min(lo[c], b.lo[c]);
        hi[c] = Math.max(hi[c], b.hi[c]);
      }
    }
    sliders.forEach(function (s, si) {
      var boxes = s.frames.map(boxOf).filter(function (b) { return b.width.every(isFinite); });
      var typical = [0, 1, 2].map(function (c) { return median(boxes.map(function (b) { return b.width[c]; })); });
      var slack = 0.25 * Math.hypot(typical[0], typical[1], typical[2]);
      boxes.forEach(function (b) {
        if (!b.width.some(function (w, c) { return w > 4 * typical[c] + slack; })) include(b);
      });
      include(boxOf(frameAt(si)));  // the frame the page opens on, whatever its size
    });
    for (var c = 0; c < 3; ++c)
      if (!(lo[c] <= hi[c])) { lo[c] = 0; hi[c] = 0; }
    var centre = [0, 1, 2].map(function (c) { return (lo[c] + hi[c]) / 2; });
    var radius = Math.max(1e-9, 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
    upright.position.set(0, 0, 0);
    var content = new THREE.Group();
    content.position.set(-centre[0], -centre[1], -centre[2]);
    upright.add(content);
    var material = new THREE.ShaderMaterial({
      uniforms: { stripes: { value: 16.0 } },
      side: THREE.DoubleSide,
      vertexShader: [
        'varying vec3 vNormal;', 'varying vec3 vWorld;', 'void main() {',
        '  vec4 w = modelMatrix * vec4(position, 1.0);', '  vWorld = w.xyz;',
        '  vNormal = mat3(modelMatrix) * normal;',
        '  gl_Position = projectionMatrix * viewMatrix * w;', '}'
      ].join('\n'),
      fragmentShader: [
        'uniform float stripes;', 'varying vec3 vNormal;', 'varying vec3 vWorld;', 'void main() {',
        '  vec3 n = normalize(vNormal);', '  if (!gl_FrontFacing) n = -n;',
        '  vec3 v = normalize(vWorld - cameraPosition);',
        '  vec3 r = reflect(v, n);',
        // light lines parallel to the world x axis, around it: the angle of r about that axis
        '  float phi = atan(r.y, r.z);',
        '  float band = smoothstep(-0.25, 0.25, cos(stripes * phi));',
        '  float diffuse = 0.45 + 0.55 * abs(dot(n, v));',
        '  vec3 light = vec3(0.98, 0.80, 0.45);', '  vec3 dark = vec3(0.12, 0.10, 0.16);',
        '  gl_FragColor = vec4(mix(dark, light, band) * diffuse, 1.0);', '}'
      ].join('\n')
    });
    var meshes = sliders.map(function (s) {
      var n = s.frames[0].points.length;
      var geometry = new THREE.BufferGeometry();
      geometry.setIndex(s.faces);
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(n), 3));
      geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(n), 3));
      var mesh = new THREE.Mesh(geometry, material);
      mesh.frustumCulled = false;
      var lines = new THREE.BufferGeometry();
      lines.setAttribute('position', new THREE.BufferAttribute(new Float32Array(s.edges.length * 3), 3));
      var net = new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0x1f4e9c }));
      net.frustumCulled = false;
      var dots = new THREE.BufferGeometry();
      dots.setAttribute('position', new THREE.BufferAttribute(new Float32Array(s.frames[0].net.length), 3));
      var points = new THREE.Points(dots, new THREE.PointsMaterial({ color: 0x1f4e9c, size: 5, sizeAttenuation: false }));
      points.frustumCulled = false;
      var holder = new THREE.Group();
      holder.add(mesh); holder.add(net); holder.add(points);
      holder.visible = false;
      content.add(holder);
      return { holder: holder, mesh: mesh, net: net, points: points };
    });
    // The direction the camera looks from: (0.9, 0.75, 1.1), above and to the side, unless it
    // sees the control nets as first shown nearly edge on: at less than 7 degrees (sine 0.12) to
    // the plane they lie closest to, whose normal is the eigenvector of the smallest eigenvalue of
    // the covariance of their points (a torus patch standing on its side was seen at 5 degrees and
    // filled 4.9 % of the view, the seed example at 5 degrees and 3.5 %, every other bundled
    // boundary at 9 or more). Then the camera stays as high above the horizon and turns about the
    // vertical to face that plane.
    function chosenDirection() {
      var fixed = new THREE.Vector3(0.9, 0.75, 1.1).normalize();
      var points = [];  // of the control nets, in three's axes (coons x, z, −y)
      sliders.forEach(function (s, si) {
        var p = frameAt(si).net;
        for (var i = 0; p && i + 2 < p.length; i += 3)
          if (isFinite(p[i]) && isFinite(p[i + 1]) && isFinite(p[i + 2])) points.push([p[i], p[i + 2], -p[i + 1]]);
      });
      if (points.length < 3) return fixed;
      var mean = [0, 1, 2].map(function (c) {
        return points.reduce(function (sum, q) { return sum + q[c]; }, 0) / points.length;
      });
      var A = [[0, 0, 0], [0, 0, 0], [0, 0, 0]], V = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
      points.forEach(function (q) {
        for (var i = 0; i < 3; ++i)
          for (var j = 0; j < 3; ++j) A[i][j] += (q[i] - mean[i]) * (q[j] - mean[j]);
      });
      for (var sweep = 0; sweep < 30; ++sweep)  // cyclic Jacobi: A → diagonal, V its eigenvectors (columns)
        for (var p = 0; p < 2; ++p)
          for (var q = p + 1; q < 3; ++q) {
            if (!(Math.abs(A[p][q]) > 1e-300)) continue;
            var theta = (A[q][q] - A[p][p]) / (2 * A[p][q]);
            var t = (theta >= 0 ? 1 : -1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
            var c = 1 / Math.sqrt(t * t + 1), sn = t * c;
            for (var k = 0; k < 3; ++k) {
              var akp = A[k][p], akq = A[k][q];
              A[k][p] = c * akp - sn * akq; A[k][q] = sn * akp + c * akq;
            }
            for (k = 0; k < 3; ++k) {
              var apk = A[p][k], aqk = A[q][k];
              A[p][k] = c * apk - sn * aqk; A[q][k] = sn * apk + c * aqk;
            }
            for (k = 0; k < 3; ++k) {
              var vkp = V[k][p], vkq = V[k][q];
              V[k][p] = c * vkp - sn * vkq; V[k][q] = sn * vkp + c * vkq;
            }
          }
      var thin = [0, 1, 2].reduce(function (a, b) { return A[b][b] < A[a][a] ? b : a; });
      var normal = new THREE.Vector3(V[0][thin], V[1][thin], V[2][thin]);
      var facing = Math.abs(fixed.dot(normal));
      var edgeOn = facing < 0.12 && Math.hypot(normal.x, normal.z) > 0.12;  // a vertical normal: any azimuth sees it alike
      document.body.setAttribute('data-view', (edgeOn ? 'turned' : 'fixed') + ' ' + facing.toFixed(3));
      if (!edgeOn) return fixed;
      var azimuth = Math.atan2(normal.x, normal.z), round = Math.hypot(fixed.x, fixed.z);
      return new THREE.Vector3(round * Math.sin(azimuth), fixed.y, round * Math.cos(azimuth));
    }
    var direction = chosenDirection();
    // The camera's distance: the one at which the 8 corners of the nets' box, as first shown,
    // fill 85 % of the view's width or height, at most the distance at which the bounding sphere
    // fits the narrower of the two fields of view (a long flat patch was left small in the middle
    // of the view), fixed at the first frame and on a change of the window's size; the wheel
    // scales it.
    var fit = null, zoom = 1;
    function fitted(aspect) {
      scene.updateMatrixWorld(true);
      var z = direction.clone(), x = new THREE.Vector3(0, 1, 0).cross(z).normalize(), y = z.clone().cross(x);
      var tanV = Math.tan(camera.fov * Math.PI / 360) * 0.85, tanH = tanV * aspect, best = 0;
      for (var k = 0; k < 8; ++k) {
        var c = new THREE.Vector3(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]);
        content.localToWorld(c);
        best = Math.max(best, c.dot(z) + Math.abs(c.dot(x)) / tanH, c.dot(z) + Math.abs(c.dot(y)) / tanV);
      }
      return best;
    }
    function place(aspect) {
      if (fit === null) {
        var half = Math.atan(Math.tan(camera.fov * Math.PI / 360) * Math.min(1, aspect));
        fit = Math.min(radius / Math.sin(half) * 1.05, Math.max(fitted(aspect), 2 * radius));
      }
      var distance = fit * zoom;
      camera.position.copy(direction).multiplyScalar(distance);
      camera.near = distance / 100; camera.far = distance * 10;
      camera.lookAt(0, 0, 0);
      camera.updateProjectionMatrix();
    }
    function render() {
      var w = canvas.clientWidth || 600, h = canvas.clientHeight || 500;
      renderer.setSize(w, h, false);
      camera.aspect = w / h;
      place(w / h);
      renderer.render(scene, camera);
    }
    var drag = null;
    canvas.addEventListener('pointerdown', function (e) { drag = [e.clientX, e.clientY]; });
    window.addEventListener('pointerup', function () { drag = null; });
    canvas.addEventListener('pointermove', function (e) {
      if (!drag) return;
      turn.rotation.y += (e.clientX - drag[0]) * 0.01;
      turn.rotation.x += (e.clientY - drag[1]) * 0.01;
      drag = [e.clientX, e.clientY];
      render();
    });
    canvas.addEventListener('wheel', function (e) {
      e.preventDefault();
      zoom *= Math.exp(e.deltaY * 0.001);
      render();
    }, { passive: false });
    window.addEventListener('resize', function () { fit = null; render(); });
    return { meshes: meshes, render: render };
  }

  function hash(array) {  // FNV-1a over the bytes of the drawn coordinates
    var bytes = new Uint8Array(array.buffer, array.byteOffset, array.byteLength), h = 0x811c9dc5;
    for (var i = 0; i < bytes.length; ++i) h = Math.imul(h ^ bytes[i], 0x01000193) >>> 0;
    return ('0000000' + h.toString(16)).slice(-8);
  }

  function draw3d(si) {
    var s = sliders[si], f = frameAt(si);
    var netCoords = new Float32Array(s.edges.length * 3);
    // s.edges holds index pairs, flattened: one line vertex per entry
    for (var k = 0; k < s.edges.length; ++k)
      for (var c = 0; c < 3; ++c) netCoords[3 * k + c] = f.net[3 * s.edges[k] + c];
    if (three) {
      three.meshes.forEach(function (m, j) { m.holder.visible = j === si; });
      var m = three.meshes[si];
      m.mesh.visible = f.ok;
      m.mesh.geometry.attributes.position.array.set(f.points);
      m.mesh.geometry.attributes.position.needsUpdate = true;
      m.mesh.geometry.attributes.normal.array.set(f.normals);
      m.mesh.geometry.attributes.normal.needsUpdate = true;
      m.net.geometry.attributes.position.array.set(netCoords);
      m.net.geometry.attributes.position.needsUpdate = true;
      m.points.geometry.attributes.position.array.set(f.net);
      m.points.geometry.attributes.position.needsUpdate = true;
      three.render();
    }
    body.setAttribute('data-net-hash', hash(netCoords));
  }

  // --- the energy curves (SVG) ---------------------------------------------------------------
  var svgNS = 'http://www.w3.org/2000/svg';
  function el(name, attributes, text) {
    var node = document.createElementNS(svgNS, name);
    for (var a in attributes) node.setAttribute(a, attributes[a]);
    if (text !== undefined) node.textContent = text;
    return node;
  }
  function drawCurves(si) {
    var s = sliders[si], svg = document.getElementById('curves');
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    var L = 56, R = 510, T = 14, B = 280;
    function x(p) { return L + (p - s.lower) / (s.upper - s.lower) * (R - L); }
    function y(v) { return B - v * (B - T); }
    svg.appendChild(el('rect', { x: L, y: T, width: R - L, height: B - T, fill: 'none', stroke: '#999' }));
    for (var t = 0; t <= 4; ++t) {
      var p = s.lower + t / 4 * (s.upper - s.lower);
      svg.appendChild(el('line', { x1: x(p), x2: x(p), y1: B, y2: B + 4, stroke: '#999' }));
      svg.appendChild(el('text', { x: x(p), y: B + 17, 'text-anchor': 'middle', 'font-size': 12 }, tick(p)));
      svg.appendChild(el('text', { x: L - 6, y: y(t / 4) + 4, 'text-anchor': 'end', 'font-size': 12 }, (t / 4).toFixed(2)));
    }
    svg.appendChild(el('text', { x: (L + R) / 2, y: B + 34, 'text-anchor': 'middle', 'font-size': 13 }, s.label));
    svg.appendChild(el('text', { x: 14, y: (T + B) / 2, 'font-size': 13, 'text-anchor': 'middle',
                                 transform: 'rotate(-90 14 ' + (T + B) / 2 + ')' }, '(energy \u2212 min) / (max \u2212 min)'));
    s.marks.forEach(function (m) {
      svg.appendChild(el('line', { x1: x(m.parameter), x2: x(m.parameter), y1: T, y2: B, stroke: '#bbb',
                                   'stroke-dasharray': '4 3' }));
      var right = x(m.parameter) > (L + R) / 2;
      svg.appendChild(el('text', { x: x(m.parameter) + (right ? -4 : 4), y: T + 26, 'font-size': 11, fill: '#777',
                                   'text-anchor': right ? 'end' : 'start' }, m.name));
    });
    var legend = document.getElementById('legend');
    legend.textContent = '';
    s.curves.forEach(function (c, ci) {
      // each curve scaled to [0, 1] over the slider's range, so that every minimum shows
      // (values beyond 100 times the upper quartile's rise above the least, a nearly singular
      // system's spike at the end of a range, run off the top instead of flattening the rest; a
      // curve its search found flat, equal to rounding, is drawn flat rather than as its noise)
      var colour = colours[ci % colours.length], least = Infinity, largest = -Infinity;
      var finite = c.values.filter(function (v) { return v !== null; }).sort(function (a, b) { return a - b; });
      var quartile = finite.length ? finite[Math.floor(0.75 * (finite.length - 1))] : 0;
      c.values.forEach(function (v) {
        if (v === null) return;
        least = Math.min(least, v);
      });
      var cap = quartile > least ? least + 100 * (quartile - least) : Infinity;
      c.values.forEach(function (v) {
        if (v !== null && v <= cap) largest = Math.max(largest, v);
      });
      var span = largest > least ? largest - least : 1;
      var flat = c.status === 'flat';
      function scaled(v) { return flat ? 0 : Math.min((v - least) / span, 1.03); }
      var path = '';
      c.values.forEach(function (v, k) {
        if (v === null) return;
        path += (path ? ' L' : 'M') + x(s.frames[k].parameter).toFixed(1) + ' ' + y(scaled(v)).toFixed(1);
      });
      svg.appendChild(el('path', { d: path, fill: 'none', stroke: colour, 'stroke-width': 1.6 }));
      var line = document.createElement('div');
      var swatch = document.createElement('span');
      swatch.className = 'swatch'; swatch.style.background = colour;
      line.appendChild(swatch);
      var text = c.name + ': ';
      if (c.optimum !== null) {
        var k = nearest(s, c.optimum), v = c.values[k];
        svg.appendChild(el('circle', { cx: x(c.optimum), cy: y(v === null ? 0 : Math.min(scaled(v), 1)), r: 4.5,
                                       fill: colour, stroke: '#fff' }));
        text += symbol(s) + '* = ' + fmt(c.optimum);
        if (c.optimum <= s.lower || c.optimum >= s.upper) text += ' (on a bound)';
      } else {
        text += 'no optimum (' + c.status + ')';
      }
      text += current[si] < 0 ? ', shown: – (between the precomputed values)' : ', shown: ' + fmt(c.values[current[si]]);
      line.appendChild(document.createTextNode(text));
      legend.appendChild(line);
    });
    var p = frameAt(si).parameter;
    svg.appendChild(el('line', { x1: x(p), x2: x(p), y1: T, y2: B, stroke: '#e00', 'stroke-width': 2, id: 'current' }));
  }

  // --- sliders ------------------------------------------------------------------------------
  var inputs = [], outputs = [];
  sliders.forEach(function (s, si) {
    var box = document.createElement('div');
    box.className = 'slider';
    var label = document.createElement('label');
    label.textContent = s.label + ' ';
    var output = document.createElement('output');
    label.appendChild(output);
    var input = document.createElement('input');
    input.type = 'range'; input.min = s.lower; input.max = s.upper; input.step = 'any';
    input.setAttribute('data-parameter', s.parameter);
    input.addEventListener('input', function () { show(si, nearest(s, Number(input.value)), false); });
    box.appendChild(label); box.appendChild(input);
    document.getElementById('controls').appendChild(box);
    inputs.push(input); outputs.push(output);
  });

  // the slider's text and the body's attributes of its current value
  function describe(si) {
    var s = sliders[si], f = frameAt(si), mu = f.mu;
    outputs[si].textContent = '= ' + fmt(f.parameter) + (mu === undefined ? '' : ' (\u03bc = ' + fmt(mu) + ')') +
                              (f.ok ? '' : ' (solve failed)');
    body.setAttribute('data-' + s.parameter, String(f.parameter));
    if (s.parameter === 'alpha') {
      if (mu === undefined) body.removeAttribute('data-mu');
      else body.setAttribute('data-mu', String(mu));
    }
  }

  function show(si, fi, moveInput) {
    active = si;
    current[si] = fi;
    var s = sliders[si], p = frameAt(si).parameter;
    if (moveInput) inputs[si].value = p;
    describe(si);
    body.setAttribute('data-shown', s.parameter);
    draw3d(si);
    drawCurves(si);
    return p;
  }

  function setValue(parameter, value) {
    for (var si = 0; si < sliders.length; ++si)
      if (sliders[si].parameter === parameter) return show(si, locate(si, Number(value)), true);
    throw new Error('no slider for ' + parameter);
  }

  function fromHash() {
    var shown = -1;
    sliders.forEach(function (s, si) {
      var m = new RegExp('[#&]' + s.parameter + '=([^&]+)').exec(window.location.hash);
      if (m && isFinite(Number(m[1]))) { current[si] = locate(si, Number(m[1])); shown = si; }
    });
    return shown;
  }

  window.coonsView = {
    setValue: setValue,
    setAlpha: function (a) { return setValue(sliders[0].parameter, a); },
    parameters: function () { return sliders.map(function (s) { return s.parameter; }); },
    exact: function (parameter) {  // true when values between the frames are solved, not rounded
      for (var si = 0; si < sliders.length; ++si)
        if (sliders[si].parameter === parameter) return !!(sliders[si].ring || sliders[si].system);
      return false;
    },
    // the page's own solve at every frame's value beside the frame written by coons (5 significant
    // digits): the largest differences of the nets, the samples (both over the largest coordinate)
    // and the unit normals, and the frames compared (the browser test of the page's solvers)
    selfCheck: function (parameter) {
      for (var si = 0; si < sliders.length; ++si) {
        var s = sliders[si];
        if (s.parameter !== parameter || !(s.ring || s.system)) continue;
        var worst = { net: 0, points: 0, normals: 0, frames: 0 }, scale = 0;
        s.frames.forEach(function (f) {
          if (!f.ok) return;
          var g = s.ring ? solvedFrame(s, f.parameter) : systemFrame(s, f.parameter);
          if (!g.ok) { worst.net = Infinity; return; }
          ++worst.frames;
          ['net', 'points', 'normals'].forEach(function (key) {
            for (var i = 0; i < f[key].length; ++i) {
              worst[key] = Math.max(worst[key], Math.abs(f[key][i] - g[key][i]));
              if (key !== 'normals') scale = Math.max(scale, Math.abs(f[key][i]));
            }
          });
        });
        worst.net /= scale || 1;
        worst.points /= scale || 1;
        return worst;
      }
      return null;
    },
    net: function () {
      return Array.prototype.map.call(frameAt(active).net, function (x, i) { return x + origin[i % 3]; });
    },
    values: function (parameter) {
      for (var si = 0; si < sliders.length; ++si)
        if (sliders[si].parameter === parameter) return sliders[si].frames.map(function (f) { return f.parameter; });
      return [];
    }
  };

  var first = fromHash();  // before the 3D set-up: the frames it opens on are inside its box
  try {
    three = setup3d();
  } catch (e) {
    record('WebGL: ' + (e && e.message ? e.message : e));
  }
  sliders.forEach(function (s, si) {
    inputs[si].value = frameAt(si).parameter;
    describe(si);
  });
  show(first >= 0 ? first : 0, current[first >= 0 ? first : 0], true);
  window.addEventListener('hashchange', function () {
    var si = fromHash();
    if (si >= 0) show(si, current[si], true);
  });
  body.setAttribute('data-ready', '1');
})();
)JS";

}  // namespace

std::string_view view_page_script() { return kScript; }
std::string_view view_page_style() { return kStyle; }

}  // namespace coons

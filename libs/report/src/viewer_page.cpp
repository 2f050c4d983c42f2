// The viewer's page (see viewer.h): HTML and a small script that builds
// the meshes from scene.js with three.js (r111 global build), plays them
// and shows the current frame's metrics. No network, no module loader, so
// it opens from disk.
#include "layers/report/viewer.h"

namespace layers::report {

const std::string& viewer_page() {
  static const std::string page = R"page(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>layers viewer</title>
<style>
  body { margin: 0; font: 14px sans-serif; background: #f4f4f4; color: #222; }
  #bar { padding: 8px 12px; display: flex; gap: 12px; align-items: center; background: #fff; border-bottom: 1px solid #ccc; }
  #slider { flex: 1; }
  #stage { position: relative; height: 62vh; }
  #stage canvas { display: block; }
  .label { position: absolute; transform: translate(-50%, 0); font-weight: bold; pointer-events: none; white-space: nowrap; }
  table { border-collapse: collapse; margin: 8px 12px; background: #fff; }
  th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
  th:first-child, td:first-child { text-align: left; }
  #note { margin: 4px 12px; color: #555; }
</style>
</head>
<body>
<div id="bar">
  <button id="play">Pause</button>
  <input id="slider" type="range" min="0" value="0" step="1">
  <span id="frame"></span>
</div>
<div id="stage"></div>
<table id="values"></table>
<p id="note">Drag to turn the scene, wheel to zoom. Body grey, inner garments blue, outer garments orange.
Metrics of the current frame, measured as the evaluation measures them (docs/metrics.md); a blank cell is not
measured for that row or frame.</p>
<script src="three.min.js"></script>
<script src="scene.js"></script>
<script>
(function () {
  'use strict';
  const S = window.LAYERS_SCENE;
  function decode(text, Type) {
    const bin = atob(text), bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  const stage = document.getElementById('stage');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setClearColor(0xf4f4f4, 1);
  stage.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.55);
  sun.position.set(1, 2, 3);
  scene.add(sun);
  const world = new THREE.Group();
  scene.add(world);

  // Meshes: one geometry per body (shared by every row) and per row's garment.
  function geometry(faces, vertices) {
    const g = new THREE.BufferGeometry();
    g.setIndex(new THREE.BufferAttribute(decode(faces, Uint32Array), 1));
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(vertices * 3), 3));
    return g;
  }
  const body = { geometry: geometry(S.body.faces, S.body.vertices), frames: decode(S.body.positions, Float32Array),
                 vertices: S.body.vertices };
  const bodyMaterial = new THREE.MeshLambertMaterial({ color: 0xdcdcdc });
  const layerMaterial = [new THREE.MeshLambertMaterial({ color: 0x3b75af, side: THREE.DoubleSide }),
                         new THREE.MeshLambertMaterial({ color: 0xe1812c, side: THREE.DoubleSide })];
  const rows = S.rows.map(function (row) {
    const group = new THREE.Group();
    group.add(new THREE.Mesh(body.geometry, bodyMaterial));
    const meshes = [body];
    S.garments.forEach(function (g, k) {
      const m = { geometry: geometry(g.faces, g.vertices), frames: decode(row.garments[k], Float32Array),
                  vertices: g.vertices };
      group.add(new THREE.Mesh(m.geometry, layerMaterial[g.layer === 0 ? 0 : 1]));
      meshes.push(m);
    });
    world.add(group);
    return { label: row.label, group: group, meshes: meshes };
  });

  // Columns side by side, spaced by the scene's width at frame 0.
  const box = new THREE.Box3();
  const p = body.frames;
  for (let i = 0; i < body.vertices; ++i) box.expandByPoint(new THREE.Vector3(p[3 * i], p[3 * i + 1], p[3 * i + 2]));
  const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
  const spacing = Math.max(size.x, size.z) * 1.5 + 0.1;
  rows.forEach(function (r, k) { r.group.position.set((k - (rows.length - 1) / 2) * spacing - centre.x, -centre.y, -centre.z); });
  const camera = new THREE.PerspectiveCamera(30, 1, 0.01, 100);
  const across = spacing * rows.length, tall = size.y * 1.25;
  let distance = 0;
  function resize() {
    const w = stage.clientWidth || 800, h = stage.clientHeight || 500;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    if (!distance) {
      const half = Math.tan(THREE.MathUtils ? THREE.MathUtils.degToRad(15) : THREE.Math.degToRad(15));
      distance = Math.max(tall / 2 / half, across / 2 / (half * camera.aspect));
    }
    camera.position.set(0, 0, distance);
    camera.lookAt(0, 0, 0);
    camera.updateProjectionMatrix();
    render();
  }

  // Labels above each column.
  const labels = rows.map(function (r) {
    const d = document.createElement('div');
    d.className = 'label';
    d.textContent = r.label;
    stage.appendChild(d);
    return d;
  });
  function placeLabels() {
    rows.forEach(function (r, k) {
      const v = new THREE.Vector3(r.group.position.x + centre.x, size.y / 2, 0).applyMatrix4(world.matrixWorld).project(camera);
      labels[k].style.left = ((v.x + 1) / 2 * stage.clientWidth) + 'px';
      labels[k].style.top = Math.max(0, (1 - v.y) / 2 * stage.clientHeight - 22) + 'px';
    });
  }
  let draws = 0;
  function render() {
    world.updateMatrixWorld(true);
    renderer.render(scene, camera);
    placeLabels();
    ++draws;
  }

  // The metrics table: a row per shown row, a column per metric.
  const table = document.getElementById('values');
  const measured = S.metrics.filter(function (m) {
    return S.rows.some(function (r) { return r.values[m.key].some(function (v) { return v !== null; }); });
  });
  const head = table.insertRow();
  ['row'].concat(measured.map(function (m) { return m.label; })).forEach(function (t, k) {
    const th = document.createElement('th');
    th.textContent = t;
    if (k > 0) th.title = measured[k - 1].description;
    head.appendChild(th);
  });
  const cells = S.rows.map(function (r) {
    const tr = table.insertRow();
    tr.insertCell().textContent = r.label;
    return measured.map(function () { return tr.insertCell(); });
  });
  function show(m, v) {
    if (v === null || v === undefined) return '';
    return m.unit === 'mm' ? v.toFixed(2) + ' mm' : (100 * v).toFixed(2) + '%';
  }

  const slider = document.getElementById('slider'), label = document.getElementById('frame');
  const button = document.getElementById('play');
  slider.max = String(S.frames - 1);
  let current = -1, playing = true;
  function setFrame(t) {
    t = Math.max(0, Math.min(S.frames - 1, Math.floor(t)));
    current = t;
    const done = new Set();
    rows.forEach(function (r) {
      r.meshes.forEach(function (m) {
        if (done.has(m.geometry)) return;
        done.add(m.geometry);
        const n = 3 * m.vertices, attr = m.geometry.attributes.position;
        attr.array.set(m.frames.subarray(t * n, (t + 1) * n));
        attr.needsUpdate = true;
        m.geometry.computeVertexNormals();
        m.geometry.computeBoundingSphere();  // for frustum culling: the meshes move
      });
    });
    slider.value = String(t);
    label.textContent = 'frame ' + t + ' of ' + S.frames + ' shown (sequence ' + S.sequence + ', ' +
      S.sequence_frames + ' frames, ' + S.fps + ' fps)';
    S.rows.forEach(function (r, i) {
      measured.forEach(function (m, k) { cells[i][k].textContent = show(m, r.values[m.key][t]); });
    });
    render();
  }
  function play() { playing = true; button.textContent = 'Pause'; }
  function pause() { playing = false; button.textContent = 'Play'; }
  button.addEventListener('click', function () { if (playing) pause(); else play(); });
  slider.addEventListener('input', function () { pause(); setFrame(Number(slider.value)); });
  setInterval(function () { if (playing) setFrame((current + 1) % S.frames); }, 1000 / S.fps);

  // Drag turns the scene about the vertical axis, the wheel zooms.
  let dragX = null;
  renderer.domElement.addEventListener('pointerdown', function (e) { dragX = e.clientX; });
  window.addEventListener('pointerup', function () { dragX = null; });
  window.addEventListener('pointermove', function (e) {
    if (dragX === null) return;
    world.rotation.y += (e.clientX - dragX) * 0.01;
    dragX = e.clientX;
    render();
  });
  renderer.domElement.addEventListener('wheel', function (e) {
    e.preventDefault();
    distance *= e.deltaY > 0 ? 1.1 : 1 / 1.1;
    resize();
  }, { passive: false });
  window.addEventListener('resize', resize);

  // For tests and scripts.
  window.layersViewer = {
    frames: S.frames,
    rows: rows.map(function (r) { return r.label; }),
    frame: function () { return current; },
    playing: function () { return playing; },
    play: play,
    pause: pause,
    setFrame: setFrame,
    draws: function () { return draws; },
    // The positions drawn now: mesh 0 is the body, 1.. the garments in order.
    positions: function (row, mesh) { return Array.from(rows[row].meshes[mesh].geometry.attributes.position.array); },
    // Share of the canvas's pixels not of the background colour.
    drawnShare: function () {
      render();
      const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const px = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      let drawn = 0;
      for (let i = 0; i < px.length; i += 4)
        if (Math.abs(px[i] - 0xf4) + Math.abs(px[i + 1] - 0xf4) + Math.abs(px[i + 2] - 0xf4) > 6) ++drawn;
      return drawn / (w * h);
    }
  };
  setFrame(0);
  resize();
})();
</script>
</body>
</html>
)page";
  return page;
}

}  // namespace layers::report

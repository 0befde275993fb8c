// Explore: the city in three.js under the orbit camera, a spherical camera bound to
// the upper hemisphere around a target that pans over the ground, with a minimap of the
// camera and the ground it sees over an overview of the city; "Render this view"
// path-traces the same camera.
// The city comes as its ground and its tiles (GET /api/tiles.json), each tile drawn at the
// level of detail its distance asks for, loaded when first needed, and left out when outside
// the view (docs/design.md, Serving: tiles); city.glb is the fallback for a city without.
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';
import {zoneColours, rgba} from './colours.js';

const degree = Math.PI / 180;
// glTF is y up with z south (generate/export/gltf_export.cpp); the city is x east, y north, z up.
const toThree = (x, y, z) => new THREE.Vector3(x, z, -y);

export class ExploreView {
  constructor(container, minimap) {
    this.container = container;
    this.minimap = minimap;
    this.renderer = new THREE.WebGLRenderer({antialias: true});
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xb8d4ee);
    this.scene.add(new THREE.HemisphereLight(0xdfefff, 0x807060, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.set(-0.6, 0.7, 0.4);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(45, 1, 1, 200000);
    // The orbit, in the city's coordinates (docs/rendering.md, Cameras: orbit:target=..,azimuth=..).
    this.orbit = {target: [0, 0, 0], azimuth: 225, elevation: 35, distance: 800};
    this.bounds = [0, 0, 1, 1];
    this.city = null;
    this.tiles = [];
    this.levels = [];
    this.layers = null;
    this.bindPointer();
    new ResizeObserver(() => this.resize()).observe(container);
  }

  // Loads the city's ground and tile index (city.glb where there is none) and puts the camera
  // over the city's `bounds` ([min_x, min_y, max_x, max_y]).
  async load(bounds, layers) {
    this.bounds = bounds;
    this.layers = layers;
    this.version = Date.now();
    const loader = new GLTFLoader();
    const index = await fetch('/api/tiles.json', {cache: 'no-store'}).then(r => (r.ok ? r.json() : null));
    if (this.city) this.scene.remove(this.city);
    for (const t of this.tiles) this.scene.remove(t.group);
    this.tiles = [];
    this.levels = index ? index.levels : [];
    this.city = (await loader.loadAsync((index ? index.ground : '/api/city.glb') + '?v=' + this.version)).scene;
    this.scene.add(this.city);
    for (const tile of index?.tiles || []) {
      const [x0, y0, z0, x1, y1, z1] = tile.box;
      const group = new THREE.Group();
      group.name = 'tile ' + tile.name;
      this.scene.add(group);
      this.tiles.push({name: tile.name, urls: tile.levels, group, loaded: [], loading: [], shown: -1,
                       box: new THREE.Box3().setFromPoints([toThree(x0, y0, z0), toThree(x1, y1, z1)])});
    }
    const [x0, y0, x1, y1] = bounds;
    const [cx, cy] = [(x0 + x1) / 2, (y0 + y1) / 2];
    this.orbit = {target: [cx, cy, this.groundHeight(cx, cy)], azimuth: 225, elevation: 35,
                  distance: 0.75 * Math.hypot(x1 - x0, y1 - y0)};
    this.overview = null;
    this.update();
    this.captureOverview();
  }

  // An air photo of the whole city, taken once from straight above at the
  // height that sees all of it, is the minimap's background: every tile at its coarsest level
  // over the ground. Until it is taken the minimap draws the zones, water and roads.
  async captureOverview() {
    const coarsest = this.levels.length - 1, tiles = this.tiles;
    for (const tile of tiles) this.loadLevel(tile, coarsest);
    await Promise.all(tiles.map(t => t.loading[coarsest]));
    if (this.tiles !== tiles) return;  // a newer city came meanwhile
    const [x0, y0, x1, y1] = this.bounds;
    const half = Math.max(x1 - x0, y1 - y0) / 2, cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    const above = new THREE.OrthographicCamera(-half, half, half, -half, 1, 2e5);
    above.position.copy(toThree(cx, cy, 1e5));
    above.up.set(0, 0, -1);  // north up
    above.lookAt(toThree(cx, cy, 0));
    const shown = tiles.map(t => [t.group.visible, t.loaded.map(scene => scene && scene.visible)]);
    for (const t of tiles) {
      t.group.visible = Boolean(t.loaded[coarsest]);
      t.loaded.forEach((scene, l) => scene && (scene.visible = l === coarsest));
    }
    const size = 256;
    const target = new THREE.WebGLRenderTarget(size, size);
    target.texture.colorSpace = THREE.SRGBColorSpace;
    this.renderer.setRenderTarget(target);
    this.renderer.render(this.scene, above);
    this.renderer.setRenderTarget(null);
    const pixels = new Uint8Array(size * size * 4);
    this.renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels);
    target.dispose();
    tiles.forEach((t, i) => {
      t.group.visible = shown[i][0];
      t.loaded.forEach((scene, l) => scene && (scene.visible = shown[i][1][l]));
    });
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = size;
    const image = canvas.getContext('2d').createImageData(size, size);
    for (let row = 0; row < size; ++row)  // WebGL's rows run bottom up
      image.data.set(pixels.subarray((size - 1 - row) * size * 4, (size - row) * size * 4), row * size * 4);
    canvas.getContext('2d').putImageData(image, 0, 0);
    this.overview = {canvas, box: [cx - half, cy - half, cx + half, cy + half]};
    this.drawMinimap();
  }

  // The city's surface under (x, y), so the target stands on a heightmap's ground, not under it.
  groundHeight(x, y) {
    const down = new THREE.Raycaster(toThree(x, y, 1e5), new THREE.Vector3(0, -1, 0));
    const hit = down.intersectObject(this.city, true)[0];
    return hit ? Math.round(hit.point.y * 100) / 100 : 0;
  }

  // The orbit camera: azimuth any way round, elevation kept in the upper hemisphere.
  setOrbit(change) {
    const o = {...this.orbit, ...change};
    o.elevation = Math.min(90, Math.max(1, o.elevation));
    o.azimuth = ((o.azimuth % 360) + 360) % 360;
    o.distance = Math.min(1e5, Math.max(5, o.distance));
    this.orbit = o;
    this.update();
  }

  spec() {
    const f = v => Number(v.toFixed(2));
    const [x, y, z] = this.orbit.target;
    return `orbit:target=${f(x)},${f(y)},${f(z)},azimuth=${f(this.orbit.azimuth)},` +
           `elevation=${f(this.orbit.elevation)},distance=${f(this.orbit.distance)}`;
  }

  // The camera's place, as Exacity's renderer puts it (render/camera.cpp, Camera::orbit).
  from() {
    const {target: [x, y, z], azimuth, elevation, distance} = this.orbit;
    const az = azimuth * degree, el = elevation * degree;
    return [x + distance * Math.cos(el) * Math.cos(az), y + distance * Math.cos(el) * Math.sin(az),
            z + distance * Math.sin(el)];
  }

  update() {
    const [fx, fy, fz] = this.from(), [tx, ty, tz] = this.orbit.target;
    this.camera.position.copy(toThree(fx, fy, fz));
    // Looking straight down, north stays up the screen.
    this.camera.up.set(0, 1, 0);
    if (this.orbit.elevation > 89.9) this.camera.up.set(0, 0, -1);
    this.camera.lookAt(toThree(tx, ty, tz));
    this.camera.near = Math.max(0.5, this.orbit.distance / 1000);
    this.camera.far = this.orbit.distance * 50 + 10000;
    this.camera.updateProjectionMatrix();
    this.camera.updateMatrixWorld();
    this.chooseLevels();
    this.draw();
    this.drawMinimap();
    document.getElementById('camera-spec').textContent = this.spec();
  }

  // Draws once per frame however often the camera moved or a tile came in since the last one.
  draw() {
    if (this.drawing) return;
    this.drawing = requestAnimationFrame(() => {
      this.drawing = null;
      this.renderer.render(this.scene, this.camera);
    });
  }

  // Each tile in the view frustum shows the level its distance asks for, loading it when first
  // asked; until it comes, the tile shows a level it has (or nothing). Tiles outside the
  // frustum are hidden and load nothing.
  chooseLevels() {
    const frustum = new THREE.Frustum().setFromProjectionMatrix(
        new THREE.Matrix4().multiplyMatrices(this.camera.projectionMatrix, this.camera.matrixWorldInverse));
    for (const tile of this.tiles) {
      tile.inView = frustum.intersectsBox(tile.box);
      if (!tile.inView) {
        tile.group.visible = false;
        tile.shown = -1;
        continue;
      }
      const distance = tile.box.distanceToPoint(this.camera.position);
      const wanted = Math.max(0, this.levels.findIndex(l => l.until === null || distance < l.until));
      if (!tile.loaded[wanted]) this.loadLevel(tile, wanted);
      // The wanted level, else the nearest level loaded, finer first.
      const order = [...tile.urls.keys()].sort((a, b) => Math.abs(a - wanted) - Math.abs(b - wanted) || a - b);
      const shown = order.find(l => tile.loaded[l]) ?? -1;
      tile.loaded.forEach((scene, l) => scene && (scene.visible = l === shown));
      tile.group.visible = shown >= 0;
      tile.shown = shown;
    }
  }

  loadLevel(tile, level) {
    if (tile.loading[level]) return;
    tile.loading[level] = new GLTFLoader().loadAsync(tile.urls[level] + '?v=' + this.version).then(gltf => {
      if (!this.tiles.includes(tile)) return;  // a newer city came meanwhile
      tile.loaded[level] = gltf.scene;
      tile.group.add(gltf.scene);
      this.update();
    }, error => {
      console.error(`tile ${tile.name} level ${level}: ${error.message || error}`);
    });
  }

  // For the browser test and the curious: tiles per level loaded and shown, tiles in view,
  // and loads under way.
  tileCounts() {
    const loaded = this.levels.map((_, l) => this.tiles.filter(t => t.loaded[l]).length);
    const shown = this.levels.map((_, l) => this.tiles.filter(t => t.shown === l).length);
    const pending = this.tiles.reduce((n, t) => n + t.loading.filter((p, l) => p && !t.loaded[l]).length, 0);
    return {tiles: this.tiles.length, inView: this.tiles.filter(t => t.inView).length, loaded, shown, pending};
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.update();
  }

  bindPointer() {
    const el = this.renderer.domElement;
    el.addEventListener('contextmenu', e => e.preventDefault());
    let last = null;
    el.addEventListener('pointerdown', e => {
      last = {x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey};
      el.setPointerCapture(e.pointerId);
    });
    // A pan ends with the target set on the ground there (one ray into the city, not one per move).
    el.addEventListener('pointerup', () => {
      if (last && last.pan && this.city) {
        const [x, y] = this.orbit.target;
        this.setOrbit({target: [x, y, this.groundHeight(x, y)]});
      }
      last = null;
    });
    el.addEventListener('pointermove', e => {
      if (!last) return;
      const dx = e.clientX - last.x, dy = e.clientY - last.y;
      last.x = e.clientX, last.y = e.clientY;
      if (!last.pan) return this.setOrbit({azimuth: this.orbit.azimuth - dx * 0.4, elevation: this.orbit.elevation + dy * 0.3});
      // Pan: the target slides over the ground, as far as the pointer moved at its distance.
      const scale = this.orbit.distance * 2 * Math.tan(this.camera.fov * degree / 2) / el.clientHeight;
      const az = this.orbit.azimuth * degree;
      const right = [-Math.sin(az), Math.cos(az)], back = [Math.cos(az), Math.sin(az)];
      const [x, y, z] = this.orbit.target;
      this.setOrbit({target: [x - (dx * right[0] + dy * back[0]) * scale, y - (dx * right[1] + dy * back[1]) * scale, z]});
    });
    el.addEventListener('wheel', e => {
      e.preventDefault();
      this.setOrbit({distance: this.orbit.distance * Math.pow(1.0015, e.deltaY)});
    }, {passive: false});
  }

  // Where the view's corner rays meet the ground (z = 0), for the minimap; an upper ray at or
  // above the horizon is replaced by the lower ray on its side followed to the city's edge
  // (a view near the horizon; render/camera.h, ground_footprint).
  groundFootprint() {
    const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]];
    const origin = this.camera.position;
    const hits = corners.map(([sx, sy]) => {
      const d = new THREE.Vector3(sx, sy, 0.5).unproject(this.camera).sub(origin).normalize();
      return d.y < -1e-6 ? origin.clone().addScaledVector(d, -origin.y / d.y) : null;
    });
    const [x0, y0, x1, y1] = this.bounds;
    const reach = 2 * Math.hypot(x1 - x0, y1 - y0) + this.orbit.distance;
    for (const [upper, lower] of [[3, 0], [2, 1]]) {
      if (hits[upper] || !hits[lower]) continue;
      const away = hits[lower].clone().sub(new THREE.Vector3(origin.x, 0, origin.z)).setY(0).normalize();
      hits[upper] = hits[lower].clone().addScaledVector(away, reach);
    }
    return hits.filter(Boolean).map(p => [p.x, -p.z]);
  }

  drawMinimap() {
    const c = this.minimap.getContext('2d');
    const [x0, y0, x1, y1] = this.bounds;
    const size = this.minimap.width, pad = 8;
    const s = (size - 2 * pad) / Math.max(x1 - x0, y1 - y0);
    const px = ([x, y]) => [pad + (x - x0) * s, size - pad - (y - y0) * s];
    c.fillStyle = '#f4f4f0';
    c.fillRect(0, 0, size, size);
    if (this.overview) {
      const [ox0, , ox1, oy1] = this.overview.box;
      const [left, top] = px([ox0, oy1]);
      c.drawImage(this.overview.canvas, left, top, (ox1 - ox0) * s, (ox1 - ox0) * s);
    }
    for (const [name, colour] of this.overview ? [] : [['zones', null], ['water', '#5b9bd5'], ['road_areas', '#6b6b6b']]) {
      const doc = this.layers?.[name];
      if (!doc) continue;
      for (const f of doc.features) {
        c.fillStyle = colour || rgba(zoneColours[f.properties.zone] || [200, 200, 200], 0.6);
        const polys = f.geometry.type === 'Polygon' ? [f.geometry.coordinates] :
                      f.geometry.type === 'MultiPolygon' ? f.geometry.coordinates : [];
        for (const poly of polys) {
          c.beginPath();
          for (const ring of poly) ring.forEach((p, i) => (i ? c.lineTo(...px(p)) : c.moveTo(...px(p))));
          c.fill('evenodd');
        }
      }
    }
    const ground = this.groundFootprint();
    if (ground.length >= 3) {
      c.beginPath();
      ground.forEach((p, i) => (i ? c.lineTo(...px(p)) : c.moveTo(...px(p))));
      c.closePath();
      c.fillStyle = '#ffd40055';
      c.strokeStyle = '#e0b000';
      c.lineWidth = 2;
      c.fill();
      c.stroke();
    }
    const [fx, fy] = this.from(), [tx, ty] = this.orbit.target;
    const [cx, cy] = px([fx, fy]), [ax, ay] = px([tx, ty]);
    c.strokeStyle = '#d00';
    c.beginPath();
    c.moveTo(cx, cy);
    c.lineTo(cx + (ax - cx) * 0.25, cy + (ay - cy) * 0.25);
    c.stroke();
    c.fillStyle = '#d00';
    c.beginPath();
    c.arc(cx, cy, 4, 0, 2 * Math.PI);
    c.fill();
  }
}

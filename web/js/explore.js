// Explore: the city in three.js under the orbit camera, a spherical camera bound to
// the upper hemisphere around a target that pans over the ground, with a minimap of the
// camera and the ground it sees over an overview of the city (3.3.4); "Render this view"
// path-traces the same camera. Walk and Fly stand the camera on the ground as the CLI's
// pedestrian and flyer cameras do (README, Rendering: cameras), moved by keys and turned by
// dragging; a click on a building shows its attributes (its buildings.geojson feature). The
// sun stands where the renderer's does and casts shadows; walls have the renderer's windows.
// The city comes as its ground and its tiles (GET /api/tiles.json), each tile drawn at the
// level of detail its distance asks for, loaded when first needed, and left out when outside
// the view (docs/design.md, Serving: tiles); city.glb is the fallback for a city without.
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';
import {zoneColours, mapColours, sun, rgba} from './colours.js';

const degree = Math.PI / 180;
// glTF is y up with z south (generate/export/gltf_export.cpp); the city is x east, y north, z up.
const toThree = (x, y, z) => new THREE.Vector3(x, z, -y);

export class ExploreView {
  constructor(container, minimap) {
    this.container = container;
    this.minimap = minimap;
    this.renderer = new THREE.WebGLRenderer({antialias: true});
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFSoftShadowMap;
    this.renderer.domElement.tabIndex = 0;  // takes the keys once clicked
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xb8d4ee);
    this.scene.add(new THREE.HemisphereLight(0xdfefff, 0x807060, 1.3));
    // The renderer's sun (render/render.h): azimuth counter-clockwise from east, elevation.
    const az = sun.azimuth * degree, el = sun.elevation * degree;
    this.sunDirection = toThree(Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el));
    this.sun = new THREE.DirectionalLight(0xffffff, 2.4);
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.set(2048, 2048);
    this.sun.shadow.bias = -0.0005;
    this.scene.add(this.sun, this.sun.target);
    this.camera = new THREE.PerspectiveCamera(45, 1, 1, 200000);
    // The orbit, in the city's coordinates (README, Rendering: orbit:target=..,azimuth=..).
    this.orbit = {target: [0, 0, 0], azimuth: 225, elevation: 35, distance: 800};
    // Walk and Fly: the CLI's pedestrian and flyer, standing at (x, y), `height` over the
    // ground (the eye's 1.7 m walking), heading counter-clockwise from east, pitch up.
    this.mode = 'orbit';
    this.stand = {x: 0, y: 0, height: 1.7, heading: 45, pitch: 0};
    this.maxDistance = 1e5;
    this.bounds = [0, 0, 1, 1];
    this.city = null;
    this.tiles = [];
    this.levels = [];
    this.layers = null;
    this.facadeWindows = facadeWindows;
    this.roofPattern = roofPattern;
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
    this.facades = index?.facades ? await fetch(index.facades + '?v=' + this.version).then(r => (r.ok ? r.json() : null)) : null;
    this.footprints = footprintGrid(layers?.buildings);
    this.city = (await loader.loadAsync((index ? index.ground : '/api/city.glb') + '?v=' + this.version)).scene;
    this.styleWalls(shadowed(this.city));
    this.scene.add(this.city);
    this.addGroundPlane();
    for (const tile of index?.tiles || []) {
      const [x0, y0, z0, x1, y1, z1] = tile.box;
      const group = new THREE.Group();
      group.name = 'tile ' + tile.name;
      this.scene.add(group);
      this.tiles.push({name: tile.name, urls: tile.levels, group, loaded: [], loading: [], shown: -1,
                       box: new THREE.Box3().setFromPoints([toThree(x0, y0, z0), toThree(x1, y1, z1)])});
    }
    this.overview = null;
    this.fit();
    this.captureOverview();
  }

  // The renderer's grass plane beyond the city (render/scene_shading.cpp): level with the
  // city's lowest ground, out past where the camera may go, so the ground has no edge.
  addGroundPlane() {
    if (this.groundPlane) this.scene.remove(this.groundPlane);
    const lowest = new THREE.Box3().setFromObject(this.city).min.y;
    const side = 1e6;
    this.groundPlane = new THREE.Mesh(new THREE.PlaneGeometry(side, side),
                                      new THREE.MeshStandardMaterial({color: new THREE.Color(...grassAlbedo), roughness: 0.9}));
    this.groundPlane.name = 'ground plane';
    this.groundPlane.rotation.x = -Math.PI / 2;
    // A few centimetres under the lowest ground, which it must not show through.
    this.groundPlane.position.set(0, lowest - 0.05, 0);
    this.groundPlane.receiveShadow = true;
    this.scene.add(this.groundPlane);
  }

  // The whole city in view from the south-west, orbiting; zoom out at most to a few times
  // its size, so it is never lost.
  fit() {
    const [x0, y0, x1, y1] = this.bounds;
    const [cx, cy] = [(x0 + x1) / 2, (y0 + y1) / 2], diagonal = Math.hypot(x1 - x0, y1 - y0);
    this.maxDistance = Math.max(5000, 8 * diagonal);
    this.mode = 'orbit';
    this.orbit = {target: [cx, cy, this.groundHeight(cx, cy)], azimuth: 225, elevation: 35, distance: 0.75 * diagonal};
    this.update();
  }

  // Orbit, walk (the CLI's pedestrian) or fly (its flyer). Walking or flying starts where
  // the orbit's camera looks from, the same way; orbiting again takes up the orbit left.
  setMode(mode) {
    if (mode === this.mode) return;
    if (mode !== 'orbit' && this.mode === 'orbit') {
      const [fx, fy, fz] = this.from(), [tx, ty] = this.orbit.target;
      const ground = this.groundHeight(fx, fy);
      const flying = mode === 'flyer';
      // A walker stands where the orbit looked, or, when that is inside a building, at the
      // first point outside it on the way back towards the orbit's camera.
      const az = this.orbit.azimuth * degree;
      let [wx, wy] = [tx, ty];
      for (let step = 1; !flying && step <= 1000 && this.footprints?.at(wx, wy) != null; ++step)
        [wx, wy] = [tx + step * Math.cos(az), ty + step * Math.sin(az)];  // a metre a step
      this.stand = {x: flying ? fx : wx, y: flying ? fy : wy, height: flying ? Math.max(2, fz - ground) : 1.7,
                    heading: (this.orbit.azimuth + 180) % 360, pitch: flying ? -this.orbit.elevation : 0};
    } else if (mode !== 'orbit') {
      this.stand.height = mode === 'flyer' ? Math.max(this.stand.height, 30) : 1.7;
    }
    this.mode = mode;
    this.update();
  }

  // Ground modes: turned, moved along the heading (forward, right) and up, in metres.
  setStand(change) {
    const s = {...this.stand, ...change};
    s.pitch = Math.min(89.9, Math.max(-89.9, s.pitch));
    s.heading = ((s.heading % 360) + 360) % 360;
    s.height = this.mode === 'pedestrian' ? 1.7 : Math.min(1e5, Math.max(0.5, s.height));
    this.stand = s;
    this.update();
  }

  move(forward, right, up = 0) {
    const h = this.stand.heading * degree;
    this.setStand({x: this.stand.x + forward * Math.cos(h) + right * Math.sin(h),
                   y: this.stand.y + forward * Math.sin(h) - right * Math.cos(h), height: this.stand.height + up});
  }

  // Keys: arrows or WASD move (pan the orbit's target, walk or fly), Q and E turn, R and F
  // tilt the orbit or raise and lower the flyer, + and - zoom, Home fits the city.
  key(e) {
    const k = e.key.length === 1 ? e.key.toLowerCase() : e.key;
    const ahead = {w: 1, ArrowUp: 1, s: -1, ArrowDown: -1}[k] || 0, side = {d: 1, ArrowRight: 1, a: -1, ArrowLeft: -1}[k] || 0;
    const turn = {q: 1, e: -1}[k] || 0, tilt = {r: 1, f: -1}[k] || 0, zoom = {'+': 1, '=': 1, '-': -1}[k] || 0;
    if (k === 'Home') return this.fit(), true;
    if (!(ahead || side || turn || tilt || zoom)) return false;
    if (this.mode === 'orbit') {
      const step = this.orbit.distance * 0.05, az = this.orbit.azimuth * degree;
      const [x, y, z] = this.orbit.target;
      // Forward is away from the camera: against the azimuth.
      const fx = -Math.cos(az), fy = -Math.sin(az);
      this.setOrbit({target: [x + (ahead * fx + side * fy) * step, y + (ahead * fy - side * fx) * step, z],
                     azimuth: this.orbit.azimuth + 5 * turn, elevation: this.orbit.elevation + 5 * tilt,
                     distance: this.orbit.distance * Math.pow(1.25, -zoom)});
      return true;
    }
    const step = this.mode === 'pedestrian' ? 2 : Math.max(5, this.stand.height / 5);
    if (turn) return this.setStand({heading: this.stand.heading + 5 * turn}), true;
    this.move((ahead + zoom) * step, side * step, this.mode === 'flyer' ? tilt * step : 0);
    return true;
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

  // The view as drawn now, RGBA rows bottom up (for the browser test).
  pixels() {
    const w = this.renderer.domElement.width, h = this.renderer.domElement.height;
    const target = new THREE.WebGLRenderTarget(w, h);
    target.texture.colorSpace = THREE.SRGBColorSpace;
    this.renderer.setRenderTarget(target);
    this.renderer.render(this.scene, this.camera);
    this.renderer.setRenderTarget(null);
    const pixels = new Uint8Array(w * h * 4);
    this.renderer.readRenderTargetPixels(target, 0, 0, w, h, pixels);
    target.dispose();
    return pixels;
  }

  // The city's surface under (x, y), so the target stands on a heightmap's ground, not under it.
  groundHeight(x, y) {
    const down = new THREE.Raycaster(toThree(x, y, 1e5), new THREE.Vector3(0, -1, 0));
    const hit = down.intersectObject(this.city, true)[0];
    return hit ? Math.round(hit.point.y * 100) / 100 : 0;
  }

  // The orbit: azimuth any way round, elevation kept in the upper hemisphere.
  setOrbit(change) {
    const o = {...this.orbit, ...change};
    o.elevation = Math.min(90, Math.max(1, o.elevation));
    o.azimuth = ((o.azimuth % 360) + 360) % 360;
    o.distance = Math.min(this.maxDistance, Math.max(5, o.distance));
    this.orbit = o;
    this.update();
  }

  spec() {
    const f = v => Number(v.toFixed(2));
    const {x: sx, y: sy, height, heading, pitch} = this.stand;
    if (this.mode === 'pedestrian') return `pedestrian:at=${f(sx)},${f(sy)},heading=${f(heading)},pitch=${f(pitch)}`;
    if (this.mode === 'flyer') return `flyer:at=${f(sx)},${f(sy)},height=${f(height)},heading=${f(heading)},pitch=${f(pitch)}`;
    const [x, y, z] = this.orbit.target;
    return `orbit:target=${f(x)},${f(y)},${f(z)},azimuth=${f(this.orbit.azimuth)},` +
           `elevation=${f(this.orbit.elevation)},distance=${f(this.orbit.distance)}`;
  }

  // The camera's place, as Exacity's renderer puts it (render/camera.cpp, Camera::orbit).
  from() {
    if (this.mode !== 'orbit') {
      const {x, y, height} = this.stand;
      return [x, y, this.groundHeight(x, y) + height];
    }
    const {target: [x, y, z], azimuth, elevation, distance} = this.orbit;
    const az = azimuth * degree, el = elevation * degree;
    return [x + distance * Math.cos(el) * Math.cos(az), y + distance * Math.cos(el) * Math.sin(az),
            z + distance * Math.sin(el)];
  }

  // Where the camera looks: the orbit's target, or a point ahead on the stand's heading.
  lookAt() {
    if (this.mode === 'orbit') return this.orbit.target;
    const [x, y, z] = this.from(), h = this.stand.heading * degree, p = this.stand.pitch * degree;
    const ahead = this.mode === 'flyer' ? 100 : 20;
    return [x + ahead * Math.cos(p) * Math.cos(h), y + ahead * Math.cos(p) * Math.sin(h), z + ahead * Math.sin(p)];
  }

  update() {
    const [fx, fy, fz] = this.from(), [tx, ty, tz] = this.lookAt();
    this.camera.position.copy(toThree(fx, fy, fz));
    // Looking straight down, north stays up the screen.
    this.camera.up.set(0, 1, 0);
    if (this.mode === 'orbit' && this.orbit.elevation > 89.9) this.camera.up.set(0, 0, -1);
    this.camera.lookAt(toThree(tx, ty, tz));
    const reach = this.mode === 'orbit' ? this.orbit.distance : this.stand.height * 10 + 200;
    this.camera.near = this.mode === 'pedestrian' ? 0.2 : Math.max(0.5, reach / 1000);
    this.camera.far = reach * 50 + 10000;
    // The sun's shadows over the ground in view around where the camera looks.
    const half = Math.min(2000, Math.max(100, reach));
    const at = toThree(tx, ty, tz);
    Object.assign(this.sun.shadow.camera, {left: -half, right: half, top: half, bottom: -half, near: 1, far: 4 * half + 6000});
    this.sun.shadow.camera.updateProjectionMatrix();
    this.sun.target.position.copy(at);
    this.sun.position.copy(at).addScaledVector(this.sunDirection, 2 * half + 3000);
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
      tile.loaded[level] = this.styleWalls(shadowed(gltf.scene));
      tile.group.add(gltf.scene);
      this.update();
    }, error => {
      console.error(`tile ${tile.name} level ${level}: ${error.message || error}`);
    }).finally(() => this.showLoading());
    this.showLoading();
  }

  // Each wall triangle takes its building's windows (GET /api/tiles/facades.json: the
  // renderer's storey, bay, window, phase, floor and eaves) as vertex attributes, its building
  // the footprint that holds a point just inside the wall; walls with none (a model's
  // foundation, a box wider than its footprint) keep their zone's middle windows.
  styleWalls(object) {
    if (!this.facades || !this.footprints) return object;
    object.updateMatrixWorld(true);
    const buildings = this.facades.buildings;
    const v = [new THREE.Vector3(), new THREE.Vector3(), new THREE.Vector3()], e1 = new THREE.Vector3(), e2 = new THREE.Vector3();
    object.traverse(o => {
      if (!o.isMesh || !/^(residential|commercial|industrial)_wall/.test(o.material.name || '')) return;
      const g = o.geometry, position = g.attributes.position, index = g.index;
      const a = new Float32Array(position.count * 4), b = new Float32Array(position.count * 4), c = new Float32Array(position.count * 2);
      const corners = index ? index.count : position.count;
      let styled = 0;
      for (let t = 0; t + 2 < corners; t += 3) {
        const at = [0, 1, 2].map(k => (index ? index.getX(t + k) : t + k));
        at.forEach((i, k) => v[k].fromBufferAttribute(position, i).applyMatrix4(o.matrixWorld));
        const outward = e1.subVectors(v[1], v[0]).cross(e2.subVectors(v[2], v[0])).normalize();
        const x = (v[0].x + v[1].x + v[2].x) / 3 - 0.05 * outward.x, y = -((v[0].z + v[1].z + v[2].z) / 3 - 0.05 * outward.z);
        const id = this.footprints.at(x, y), f = id === null ? null : buildings[id];
        if (!f) continue;
        ++styled;
        for (const i of at) {
          a.set([f[0], f[1], f[2], f[5]], i * 4);
          b.set([f[3], f[4], f[6], f[7]], i * 4);
          c.set([f[8], f[9]], i * 2);
        }
      }
      g.setAttribute('facadeA', new THREE.BufferAttribute(a, 4));
      g.setAttribute('facadeB', new THREE.BufferAttribute(b, 4));
      g.setAttribute('facadeC', new THREE.BufferAttribute(c, 2));
      g.userData.styledTriangles = styled;
    });
    return object;
  }

  // How many tiles are still coming, over the view while any are.
  showLoading() {
    const pending = this.tileCounts().pending, box = document.getElementById('tiles-loading');
    box.hidden = pending === 0;
    box.textContent = `Loading ${pending} tile${pending === 1 ? '' : 's'}…`;
  }

  // The building under the pointer: the first surface a ray from the camera meets, a little
  // past it (inside the building, not on its wall), found among buildings.geojson's
  // footprints; null for none.
  buildingAt(clientX, clientY) {
    const r = this.renderer.domElement.getBoundingClientRect();
    const ray = new THREE.Raycaster();
    ray.setFromCamera(new THREE.Vector2((clientX - r.left) / r.width * 2 - 1, -(clientY - r.top) / r.height * 2 + 1), this.camera);
    // The ray meets hidden levels too: the first hit on something shown.
    const drawn = o => { for (; o; o = o.parent) if (!o.visible) return false; return true; };
    const hit = ray.intersectObjects([this.city, ...this.tiles.map(t => t.group)], true).find(h => drawn(h.object));
    if (!hit) return null;
    const p = hit.point.clone().addScaledVector(ray.ray.direction, 0.05);
    const x = p.x, y = -p.z;
    return (this.layers?.buildings?.features || []).find(f => covers(f.geometry, x, y)) || null;
  }

  showBuilding(feature) {
    const box = document.getElementById('building-info');
    box.hidden = !feature;
    if (!feature) return;
    const p = feature.properties;
    const rows = [['building', p.id], ['zone', p.zone], ['height', typeof p.height === 'number' ? `${p.height.toFixed(1)} m` : p.height],
                  ['lot', p.lot], ['model', p.model ?? 'extruded'], ['roof', p.roof]].filter(([, v]) => v !== undefined && v !== null);
    box.replaceChildren(...rows.flatMap(([k, v]) => [Object.assign(document.createElement('dt'), {textContent: k}),
                                                       Object.assign(document.createElement('dd'), {textContent: String(v)})]));
    box.dataset.id = p.id;
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
    el.addEventListener('keydown', e => {
      if (!e.ctrlKey && !e.metaKey && !e.altKey && this.key(e)) e.preventDefault();
    });
    el.addEventListener('pointerdown', e => {
      last = {x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey, moved: 0};
      el.setPointerCapture(e.pointerId);
      el.focus();
    });
    // A pan ends with the target set on the ground there (one ray into the city, not one per
    // move); a click that did not move picks the building under it.
    el.addEventListener('pointerup', e => {
      if (last && last.pan && this.city && this.mode === 'orbit') {
        const [x, y] = this.orbit.target;
        this.setOrbit({target: [x, y, this.groundHeight(x, y)]});
      }
      if (last && last.moved < 4 && e.button === 0 && this.city) this.showBuilding(this.buildingAt(e.clientX, e.clientY));
      last = null;
    });
    el.addEventListener('pointermove', e => {
      if (!last) return;
      const dx = e.clientX - last.x, dy = e.clientY - last.y;
      last.x = e.clientX, last.y = e.clientY;
      last.moved += Math.abs(dx) + Math.abs(dy);
      if (this.mode !== 'orbit') return this.setStand({heading: this.stand.heading - dx * 0.2, pitch: this.stand.pitch - dy * 0.2});
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
      if (this.mode !== 'orbit') return this.move(-e.deltaY * (this.mode === 'pedestrian' ? 0.02 : Math.max(0.05, this.stand.height / 500)), 0);
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
    c.fillStyle = mapColours.background;
    c.fillRect(0, 0, size, size);
    if (this.overview) {
      const [ox0, , ox1, oy1] = this.overview.box;
      const [left, top] = px([ox0, oy1]);
      c.drawImage(this.overview.canvas, left, top, (ox1 - ox0) * s, (ox1 - ox0) * s);
    }
    for (const [name, colour] of this.overview ? [] : [['zones', null], ['water', mapColours.water], ['road_areas', mapColours.road]]) {
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
    const [fx, fy] = this.from(), [tx, ty] = this.lookAt();
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

// The renderer's windows (render/facade.cpp, window_at) on the walls of extruded buildings,
// city.glb's materials "<zone>_wall_<n>": rows of windows a storey apart and bays along the
// wall, a commercial building's ground floor shop windows, a curtain wall's dark spandrels
// between its storeys' glass. Each building's own storey, bay, window, phase, floor and
// eaves are the renderer's (vertex attributes: ExploreView.styleWalls); a wall whose
// building is not known takes its zone's middle values below, counted from height 0.
// Far away, where a pixel spans a bay, the wall takes the windows' share of its area.
const facadeStyles = {  // storey, bay, window share of a bay, sill and head shares of a storey, shopfront
  residential: [3.0, 3.1, 0.425, 0.33, 0.77, 0],
  commercial: [3.8, 2.8, 0.675, 0.22, 0.83, 1],
  industrial: [5.25, 5.0, 0.625, 0.55, 0.85, 0],
};
// Off only for the browser test, to see what the windows and the roofs' tiles change.
export const facadeWindows = {value: 1};
export const roofPattern = {value: 1};
const windowAlbedo = new THREE.Color(0.04, 0.05, 0.06);  // palette.h, kWindowAlbedo (linear)
const grassAlbedo = [0.30, 0.45, 0.20];  // palette.h, kGrassAlbedo (linear)

function withWindows(material, style) {
  material.onBeforeCompile = shader => {
    shader.uniforms.facadeStyle = {value: new THREE.Vector4(...style.slice(0, 4))};
    shader.uniforms.facadeShop = {value: new THREE.Vector2(style[4], style[5])};
    shader.uniforms.facadeWindows = facadeWindows;
    shader.uniforms.windowAlbedo = {value: windowAlbedo};
    // In city.glb's own frame (about its local origin, which every tile shares): small
    // numbers, so the pattern stays put in single floats.
    shader.vertexShader = `varying vec3 vCityPosition;
        varying vec3 vCityNormal;
        attribute vec4 facadeA;  // storey, bay, window, phase (storey 0: not known)
        attribute vec4 facadeB;  // sill, head, floor, eaves
        attribute vec2 facadeC;  // shopfront, curtain wall
        varying vec4 vFacadeA;
        varying vec4 vFacadeB;
        varying vec2 vFacadeC;
        ` + shader.vertexShader.replace(
        '#include <begin_vertex>', `#include <begin_vertex>
          vCityPosition = transformed;
          vCityNormal = objectNormal;
          vFacadeA = facadeA;
          vFacadeB = facadeB;
          vFacadeC = facadeC;`);
    shader.fragmentShader = `varying vec3 vCityPosition;
        varying vec3 vCityNormal;
        varying vec4 vFacadeA;
        varying vec4 vFacadeB;
        varying vec2 vFacadeC;
        uniform vec4 facadeStyle;  // storey, bay, window, sill
        uniform vec2 facadeShop;   // head, shopfront
        uniform float facadeWindows;
        uniform vec3 windowAlbedo;
        ` + shader.fragmentShader.replace('#include <color_fragment>', `#include <color_fragment>
          float windowed = 0.0;
          float h = vCityPosition.y;
          // Along the wall: glTF's x east and z south (render/facade.h, along_wall).
          float along = vCityPosition.x * vCityNormal.z - vCityPosition.z * vCityNormal.x;
          float spandrel = 0.0;
          if (facadeWindows > 0.5 && abs(vCityNormal.y) < 0.3 && vFacadeA.x > 0.0) {
            // This building's own style, as render/facade.cpp's window_at reads it.
            float storey = vFacadeA.x, bayWidth = vFacadeA.y, pane = vFacadeA.z, phase = vFacadeA.w;
            float sill = vFacadeB.x, head = vFacadeB.y, floorZ = vFacadeB.z, eaves = vFacadeB.w;
            bool shop = vFacadeC.x > 0.5;
            float above = h - floorZ;
            if (above >= 0.0 && h <= eaves - 0.4) {
              if (shop && above < 4.5) {
                float bay = fract((along - phase) / (2.0 * bayWidth));
                windowed = float(above > 0.4 && above < 3.4 && bay > 0.05 && bay < 0.95);
              } else {
                float up = shop ? above - 4.5 : above;
                float row = floor(up / storey);
                bool below = floorZ + (shop ? 4.5 : 0.0) + (row + head) * storey <= eaves - 0.4;
                float bay = fract((along - phase) / bayWidth), level = fract(up / storey);
                windowed = float(below && level > sill && level < head && abs(bay - 0.5) < pane / 2.0);
                spandrel = float(vFacadeC.y > 0.5 && windowed < 0.5);
              }
            }
            float share = pane * (head - sill);
            float blur = clamp(2.0 * max(fwidth(along) / bayWidth, fwidth(h) / storey) - 0.5, 0.0, 1.0);
            windowed = mix(windowed, share, blur);
            spandrel *= 1.0 - blur;
          } else if (facadeWindows > 0.5 && abs(vCityNormal.y) < 0.3 && h > 0.0) {
            float share = facadeStyle.z * (facadeShop.x - facadeStyle.w);
            if (facadeShop.y > 0.5 && h < 4.5) {
              float bay = fract(along / (2.0 * facadeStyle.y));
              windowed = float(h > 0.4 && h < 3.4 && bay > 0.05 && bay < 0.95);
            } else {
              float storey = fract((facadeShop.y > 0.5 ? h - 4.5 : h) / facadeStyle.x);
              float bay = fract(along / facadeStyle.y);
              windowed = float(storey > facadeStyle.w && storey < facadeShop.x && abs(bay - 0.5) < facadeStyle.z / 2.0);
            }
            float blur = clamp(2.0 * max(fwidth(along) / facadeStyle.y, fwidth(h) / facadeStyle.x) - 0.5, 0.0, 1.0);
            windowed = mix(windowed, share, blur);
          }
          diffuseColor.rgb = mix(diffuseColor.rgb, windowAlbedo, windowed);
          // A curtain wall's spandrels: opaque dark glass (the renderer's tint × 0.14).
          diffuseColor.rgb = mix(diffuseColor.rgb, vec3(0.1), spandrel);`).replace(
        '#include <roughnessmap_fragment>', `#include <roughnessmap_fragment>
          roughnessFactor = mix(roughnessFactor, 0.15, max(windowed, spandrel));`);
  };
  material.customProgramCacheKey = () => 'exacity-facade';
}

// The renderer's roofs (render/facade.cpp, roof_material) on city.glb's materials
// "<zone>_roof_<n>": a pitched roof in rows of tiles 0.3 m apart down its slope, 0.25 m wide,
// each row shifted half a tile, the lower edge of a row in the shadow of the row above and
// each tile a shade of its own; a flat roof gravel, fine grains over broad stains (value
// noise here, Perlin there). Far away, where a pixel spans a tile, the roof takes the
// pattern's mean shade, so far roofs do not shimmer.
function withRoofTiles(material) {
  material.onBeforeCompile = shader => {
    shader.uniforms.roofPattern = roofPattern;
    shader.vertexShader = 'varying vec3 vRoofPosition;\nvarying vec3 vRoofNormal;\n' + shader.vertexShader.replace(
        '#include <begin_vertex>', `#include <begin_vertex>
          vRoofPosition = transformed;
          vRoofNormal = objectNormal;`);
    shader.fragmentShader = `varying vec3 vRoofPosition;
        varying vec3 vRoofNormal;
        uniform float roofPattern;
        float roofHash(vec2 c) { return fract(sin(dot(c, vec2(12.9898, 78.233))) * 43758.5453); }
        float roofNoise(vec2 p) {  // value noise, -1 to 1
          vec2 i = floor(p), f = fract(p), u = f * f * (3.0 - 2.0 * f);
          float a = roofHash(i), b = roofHash(i + vec2(1, 0)), c = roofHash(i + vec2(0, 1)), d = roofHash(i + vec2(1, 1));
          return 2.0 * mix(mix(a, b, u.x), mix(c, d, u.x), u.y) - 1.0;
        }
        ` + shader.fragmentShader.replace('#include <color_fragment>', `#include <color_fragment>
          if (roofPattern > 0.5) {
            // The city's x east, y north, z up: glTF's x, -z and y.
            vec2 p = vec2(vRoofPosition.x, -vRoofPosition.z);
            vec3 n = normalize(vec3(vRoofNormal.x, -vRoofNormal.z, vRoofNormal.y));
            float shade;
            if (abs(n.z) > 0.98) {
              float grain = roofNoise(p * 9.0), stain = 0.5 * roofNoise(p * 0.15) + 0.25 * roofNoise(p * 0.3);
              float blur = clamp(2.0 * fwidth(p.x * 9.0) - 0.5, 0.0, 1.0);
              shade = clamp(0.9 + 0.25 * grain * (1.0 - blur) + 0.3 * stain, 0.5, 1.3);
            } else {
              vec2 d = normalize(n.xy);
              float down = dot(p, d) / 0.3, across = dot(p, vec2(-d.y, d.x)) / 0.25;
              float row = floor(down), shifted = across + (mod(row, 2.0) > 0.5 ? 0.5 : 0.0);
              shade = 0.88 + 0.24 * roofHash(vec2(row, floor(shifted)));
              if (fract(down) > 0.8) shade *= 0.6;
              if (fract(shifted) < 0.06) shade *= 0.75;
              float blur = clamp(2.0 * max(fwidth(down), fwidth(across)) - 0.5, 0.0, 1.0);
              shade = mix(shade, 0.92 * 0.985, blur);  // the rows' and joints' mean
            }
            diffuseColor.rgb *= shade;
          }`);
  };
  material.customProgramCacheKey = () => 'exacity-roof';
}

// Every mesh casts and takes the sun's shadows; walls get their windows, roofs their tiles.
function shadowed(object) {
  object.traverse(o => {
    if (!o.isMesh) return;
    o.castShadow = o.receiveShadow = true;
    const wall = /^(residential|commercial|industrial)_wall/.exec(o.material.name || '');
    const roof = /^(residential|commercial|industrial)_roof/.test(o.material.name || '');
    // city.glb has no normals (its triangles do not share corners): the faces' own.
    if ((wall || roof) && !o.geometry.attributes.normal) o.geometry.computeVertexNormals();
    if (roof && !o.material.userData.tiles) {
      withRoofTiles(o.material);
      o.material.userData.tiles = true;
    }
    if (wall && !o.material.userData.windows) {
      withWindows(o.material, facadeStyles[wall[1]]);
      o.material.userData.windows = true;
    }
  });
  return object;
}

// buildings.geojson's footprints in square cells, to find the one holding a point: its
// `at(x, y)` is the building's id, or null.
function footprintGrid(buildings) {
  if (!buildings) return null;
  const cell = 32, cells = new Map();
  const key = (i, j) => i * 100003 + j;
  for (const f of buildings.features) {
    const box = [Infinity, Infinity, -Infinity, -Infinity];
    const grow = c => (typeof c[0] === 'number' ? (box[0] = Math.min(box[0], c[0]), box[1] = Math.min(box[1], c[1]),
                                                   box[2] = Math.max(box[2], c[0]), box[3] = Math.max(box[3], c[1])) : c.forEach(grow));
    grow(f.geometry.coordinates);
    for (let i = Math.floor(box[0] / cell); i <= Math.floor(box[2] / cell); ++i)
      for (let j = Math.floor(box[1] / cell); j <= Math.floor(box[3] / cell); ++j) {
        if (!cells.has(key(i, j))) cells.set(key(i, j), []);
        cells.get(key(i, j)).push(f);
      }
  }
  return {at: (x, y) => {
    const f = (cells.get(key(Math.floor(x / cell), Math.floor(y / cell))) || []).find(f => covers(f.geometry, x, y));
    return f ? f.properties.id : null;
  }};
}

// Whether (x, y) lies in a GeoJSON Polygon or MultiPolygon (even-odd over its rings).
function covers(geometry, x, y) {
  const polygons = geometry.type === 'Polygon' ? [geometry.coordinates] : geometry.type === 'MultiPolygon' ? geometry.coordinates : [];
  return polygons.some(rings => {
    let inside = false;
    for (const ring of rings)
      for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
        const [xi, yi] = ring[i], [xj, yj] = ring[j];
        if ((yi > y) !== (yj > y) && x < xi + (y - yi) * (xj - xi) / (yj - yi)) inside = !inside;
      }
    return inside;
  });
}

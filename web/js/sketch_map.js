// The sketch on a 2D map in metres (docs/serve.md, The page): zones drawn by clicking vertices, roads
// as polylines with a width, selected by click, moved by Ctrl-drag, deleted with Del; the
// heightmap under them in grey with its water in blue, a labelled grid, a scale bar and the
// pointer's coordinates.
import {zoneColours, roadColours, defaultWidths, rgba} from './colours.js';

const ol = window.ol;

// Sketch coordinates are metres, x east and y north (docs/sketch.md): a plain metric plane.
export const metres = new ol.proj.Projection({code: 'exacity-metres', units: 'm', extent: [-1e7, -1e7, 1e7, 1e7]});
const geojson = new ol.format.GeoJSON({dataProjection: metres, featureProjection: metres});
const zoneTypes = Object.keys(zoneColours);
const roadClasses = Object.keys(roadColours);
const defaults = (ns) => (typeof ns === 'function' ? ns : ns.defaults);

function sketchStyle(feature, resolution, selected) {
  const zone = feature.get('zone'), road = feature.get('road');
  const styles = [];
  if (zone) {
    const c = zoneColours[zone] || [128, 128, 128];
    styles.push(new ol.style.Style({fill: new ol.style.Fill({color: rgba(c, 0.4)}),
                                    stroke: new ol.style.Stroke({color: rgba(c, 0.95), width: 2})}));
  } else if (road) {
    const width = Math.max(2, (feature.get('width') || defaultWidths[road] || 8) / resolution);
    styles.push(new ol.style.Style({stroke: new ol.style.Stroke({color: roadColours[road] || '#000', width,
                                                                 lineCap: 'round', lineJoin: 'round'})}));
  }
  if (selected) {
    styles.unshift(new ol.style.Style({stroke: new ol.style.Stroke({color: '#ffd400', width: zone ? 6 : 10})}));
    styles.push(new ol.style.Style({
      image: new ol.style.Circle({radius: 4, fill: new ol.style.Fill({color: '#ffd400'}),
                                  stroke: new ol.style.Stroke({color: '#000', width: 1})}),
      geometry: f => {
        const g = f.getGeometry();
        const coords = g.getType() === 'Polygon' ? g.getCoordinates().flat() :
                       g.getType() === 'LineString' ? g.getCoordinates() : [];
        return new ol.geom.MultiPoint(coords);
      }}));
  }
  return styles;
}

// Grid lines a hundred to two hundred and fifty pixels apart, at 1, 2 or 5 times a power of
// ten metres, and their labels: each x along the top edge, each y along the left one, none
// in the top left corner, where the zoom buttons are and the two rows of labels would meet.
const kCornerWidth = 32, kCornerHeight = 72;  // pixels: OpenLayers' zoom buttons, and a label's height under them
function gridLines(extent, resolution) {
  const least = resolution * 100, power = Math.pow(10, Math.floor(Math.log10(least)));
  const step = [1, 2, 5, 10].map(m => m * power).find(s => s >= least);
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const lines = [], labels = [];
  const [x0, y0, x1, y1] = extent;
  const label = (at, text, axis) => {
    const f = new ol.Feature(new ol.geom.Point(at));
    f.setProperties({label: text, axis});
    labels.push(f);
  };
  // Multiples of the step counted, not summed, so a label reads 0.3 and not 0.30000000000000004.
  for (let i = Math.ceil(x0 / step); i * step <= x1 && lines.length < 400; ++i) {
    lines.push(new ol.Feature(new ol.geom.LineString([[i * step, y0], [i * step, y1]])));
    if (i * step > x0 + kCornerWidth * resolution) label([i * step, y1], `${(i * step).toFixed(digits)} m`, 'x');
  }
  for (let i = Math.ceil(y0 / step); i * step <= y1 && lines.length < 800; ++i) {
    lines.push(new ol.Feature(new ol.geom.LineString([[x0, i * step], [x1, i * step]])));
    if (i * step < y1 - kCornerHeight * resolution) label([x0, i * step], `${(i * step).toFixed(digits)} m`, 'y');
  }
  return {lines, labels};
}

const gridLabelStyle = f => new ol.style.Style({text: new ol.style.Text({
  text: f.get('label'), font: '10px system-ui, sans-serif', fill: new ol.style.Fill({color: '#555'}),
  stroke: new ol.style.Stroke({color: '#fff', width: 3}), textAlign: 'left',
  textBaseline: f.get('axis') === 'x' ? 'top' : 'bottom', offsetX: 3, offsetY: f.get('axis') === 'x' ? 3 : -2})});

// The sketch's metres to lon/lat and back, from the server's grid of PROJ's lon/lat over the
// sketch (GET /api/lonlat): bilinear within a cell, the edge cells' continued beyond; the
// inverse by Newton's method on it. Registered with OpenLayers, so a basemap in Web
// Mercator or lon/lat is reprojected under the sketch.
function registerLonLat(grid) {
  const [x0, y0, x1, y1] = grid.box, n = grid.side, dx = (x1 - x0) / (n - 1), dy = (y1 - y0) / (n - 1);
  const at = (col, row) => grid.lonlat[row * n + col];
  const toLonLat = ([x, y]) => {
    const fc = (x - x0) / dx, fr = (y - y0) / dy;
    const c = Math.min(n - 2, Math.max(0, Math.floor(fc))), r = Math.min(n - 2, Math.max(0, Math.floor(fr)));
    const u = fc - c, v = fr - r;
    const [lon, lat] = [0, 1].map(k => (1 - u) * (1 - v) * at(c, r)[k] + u * (1 - v) * at(c + 1, r)[k] +
                                       (1 - u) * v * at(c, r + 1)[k] + u * v * at(c + 1, r + 1)[k]);
    return [lon, Math.max(-85, Math.min(85, lat))];
  };
  const fromLonLat = ([lon, lat]) => {
    let p = [(x0 + x1) / 2, (y0 + y1) / 2];
    for (let i = 0; i < 6; ++i) {
      const f = toLonLat(p), fx = toLonLat([p[0] + dx, p[1]]), fy = toLonLat([p[0], p[1] + dy]);
      const a = (fx[0] - f[0]) / dx, b = (fy[0] - f[0]) / dy, c = (fx[1] - f[1]) / dx, d = (fy[1] - f[1]) / dy;
      const e0 = lon - f[0], e1 = lat - f[1], det = a * d - b * c;
      p = [p[0] + (d * e0 - b * e1) / det, p[1] + (a * e1 - c * e0) / det];
    }
    return p;
  };
  ol.proj.addCoordinateTransforms(metres, 'EPSG:4326', toLonLat, fromLonLat);
  ol.proj.addCoordinateTransforms(metres, 'EPSG:3857', c => ol.proj.fromLonLat(toLonLat(c)),
                                  c => fromLonLat(ol.proj.toLonLat(c)));
  return {toLonLat, fromLonLat};
}

export class SketchMap {
  // `edited` is called after every edit of the drawing; `selected` with the selected feature or null.
  constructor(target, {edited, selected}) {
    this.edited = edited;
    this.onSelected = selected;
    this.order = 0;
    this.doc = {type: 'FeatureCollection', features: []};
    this.source = new ol.source.Vector();
    this.layer = new ol.layer.Vector({source: this.source, style: (f, r) => sketchStyle(f, r, false)});
    this.gridSource = new ol.source.Vector();
    this.grid = new ol.layer.Vector({source: this.gridSource,
                                     style: new ol.style.Style({stroke: new ol.style.Stroke({color: '#0002', width: 1})})});
    // The labels above everything, the city included; the lines under it.
    this.gridLabels = new ol.layer.Vector({source: new ol.source.Vector(), style: gridLabelStyle,
                                           declutter: true});
    this.heightmap = new ol.layer.Image({opacity: 0.85});
    // A basemap the user names, under everything; none until then: XYZ tiles, or a GeoTIFF
    // of the work folder that the server warps into the sketch's coordinates.
    this.basemap = new ol.layer.Tile({opacity: 0.8});
    this.geotiff = new ol.layer.Image({opacity: 0.8});
    this.city = new ol.layer.Group({layers: []});
    this.map = new ol.Map({
      target,
      layers: [this.basemap, this.geotiff, this.heightmap, this.grid, this.city, this.layer, this.gridLabels],
      view: new ol.View({projection: metres, center: [0, 0], resolution: 2}),
      controls: defaults(ol.control.defaults)().extend([
        new ol.control.ScaleLine({units: 'metric'}),
        // The pointer's place in the sketch's own coordinates, to the decimetre.
        new ol.control.MousePosition({projection: metres, placeholder: '',
                                      coordinateFormat: c => `x ${c[0].toFixed(1)} m, y ${c[1].toFixed(1)} m`}),
      ]),
      // A double click closes a zone; it must not zoom too.
      interactions: defaults(ol.interaction.defaults)({doubleClickZoom: false}),
    });
    this.map.on('moveend', () => this.drawGrid());

    // Every click selects (double clicks mean nothing in this mode), without waiting to see
    // whether a second click follows.
    this.select = new ol.interaction.Select({layers: [this.layer], hitTolerance: 5, condition: ol.events.condition.click,
                                             style: (f, r) => sketchStyle(f, r, true)});
    this.select.on('select', () => this.onSelected(this.selectedFeature()));
    this.modify = new ol.interaction.Modify({features: this.select.getFeatures()});
    this.modify.on('modifyend', () => this.edited());
    // Elements are moved by holding Ctrl and dragging them.
    this.translate = new ol.interaction.Translate({layers: [this.layer], hitTolerance: 5,
                                                   condition: e => ol.events.condition.platformModifierKeyOnly(e)});
    this.translate.on('translateend', () => this.edited());
    for (const i of [this.select, this.modify, this.translate]) this.map.addInteraction(i);
    this.snap = new ol.interaction.Snap({source: this.source});
    this.map.addInteraction(this.snap);
    this.draw = null;
    this.setTool('select');
  }

  // 'select', a zone type or a road class.
  setTool(tool) {
    if (this.draw) this.map.removeInteraction(this.draw);
    this.draw = null;
    this.tool = tool;
    const drawing = tool !== 'select';
    this.select.setActive(!drawing);
    this.modify.setActive(!drawing);
    if (drawing) {
      this.select.getFeatures().clear();
      this.onSelected(null);
      const zone = zoneTypes.includes(tool);
      this.draw = new ol.interaction.Draw({source: this.source, type: zone ? 'Polygon' : 'LineString'});
      this.draw.on('drawend', e => {
        const f = e.feature;
        if (zone) f.set('zone', tool);
        else f.setProperties({road: tool, width: defaultWidths[tool]});
        f.exacityOrder = ++this.order;
        setTimeout(() => this.edited());  // once the feature is in the source
      });
      this.map.addInteraction(this.draw);
      // Snap after Draw, so it sees the pointer first.
      this.map.removeInteraction(this.snap);
      this.map.addInteraction(this.snap);
    }
  }

  // Enter closes the zone or road being drawn.
  finishDrawing() { if (this.draw) this.draw.finishDrawing(); }
  abortDrawing() { if (this.draw) this.draw.abortDrawing(); }

  selectedFeature() {
    const features = this.select.getFeatures();
    return features.getLength() === 1 ? features.item(0) : null;
  }

  deleteSelected() {
    const features = this.select.getFeatures().getArray().slice();
    if (!features.length) return false;
    this.select.getFeatures().clear();
    for (const f of features) this.source.removeFeature(f);
    this.onSelected(null);
    this.edited();
    return true;
  }

  // The sketch as GeoJSON: the document's other members kept, features in drawing order
  // (where zones overlap, the later one wins: docs/sketch.md).
  sketch() {
    const features = this.source.getFeatures().slice().sort((a, b) => a.exacityOrder - b.exacityOrder);
    const doc = {...this.doc};
    doc.type = 'FeatureCollection';
    doc.features = features.map(f => geojson.writeFeatureObject(f, {decimals: 3}));
    for (const f of doc.features) delete f.id;
    return doc;
  }

  // Shows `doc`; `fit` moves the view onto its features.
  load(doc, fit) {
    this.select.getFeatures().clear();
    this.onSelected(null);
    this.doc = {...doc};
    delete this.doc.features;
    this.source.clear();
    const features = geojson.readFeatures({type: 'FeatureCollection', features: doc.features || []});
    for (const f of features) f.exacityOrder = ++this.order;
    this.source.addFeatures(features);
    this.showHeightmap();
    if (fit && features.length) this.map.getView().fit(this.source.getExtent(), {padding: [40, 40, 40, 40]});
    // Clicks find features in the last frame drawn: draw these now, not at the next frame.
    this.map.renderSync();
  }

  settings() { return this.doc.exacity || {}; }
  setSettings(exacity) { this.doc = {...this.doc, exacity}; }

  showHeightmap() {
    const terrain = this.settings().terrain;
    if (!terrain || !terrain.bounds) return this.heightmap.setSource(null);
    this.heightmap.setSource(new ol.source.ImageStatic({
      url: '/api/heightmap.png?v=' + Date.now(), imageExtent: terrain.bounds, projection: metres}));
  }

  // An XYZ tile URL (`{z}`, `{x}`, `{y}`, in Web Mercator) under a sketch with a place on Earth
  // (`grid`, GET /api/lonlat); null or an empty URL removes it.
  setBasemap(url, grid) {
    if (!url || !grid?.epsg) return this.basemap.setSource(null);
    this.lonLat = registerLonLat(grid);
    this.basemap.setSource(new ol.source.XYZ({url, projection: 'EPSG:3857', maxZoom: 19}));
  }

  // A GeoTIFF as the server placed it (GET /api/basemap: its name and extent in the sketch's
  // coordinates); null removes it.
  setGeoTiff(placed) {
    if (!placed) return this.geotiff.setSource(null);
    this.geotiff.setSource(new ol.source.ImageStatic({
      url: `/api/basemap.png?file=${encodeURIComponent(placed.file)}&v=${Date.now()}`,
      imageExtent: placed.extent, projection: metres}));
  }

  drawGrid() {
    const view = this.map.getView();
    const {lines, labels} = gridLines(view.calculateExtent(this.map.getSize()), view.getResolution());
    this.gridSource.clear();
    this.gridSource.addFeatures(lines);
    this.gridLabels.getSource().clear();
    this.gridLabels.getSource().addFeatures(labels);
  }
}

// The generated city's layers drawn as vector layers over the sketch, and the report's
// figures beside them (README, Outputs).
import {zoneColours, mapColours, rgba} from './colours.js';
import {metres} from './sketch_map.js';

const ol = window.ol;
const geojson = new ol.format.GeoJSON({dataProjection: metres, featureProjection: metres});

const fill = c => new ol.style.Fill({color: c});
const stroke = (c, width) => new ol.style.Stroke({color: c, width});
// The SVG map's colours (generate/city/palette.h); lots half opaque, as the map draws them.
const colours = {water: mapColours.water, green: mapColours.zones.park, lot: mapColours.lot_fill + '80',
                 lotEdge: mapColours.lot_edge, sidewalk: mapColours.sidewalk, carriageway: mapColours.road,
                 building: mapColours.building, buildingEdge: mapColours.building_edge};
// In drawing order, bottom first.
const layerStyles = {
  zones: f => new ol.style.Style({fill: fill(rgba(zoneColours[f.get('zone')] || [200, 200, 200], 0.35))}),
  water: () => new ol.style.Style({fill: fill(colours.water)}),
  blocks: f => new ol.style.Style({fill: f.get('green') ? fill(colours.green) : undefined, stroke: stroke('#0004', 1)}),
  lots: () => new ol.style.Style({fill: fill(colours.lot), stroke: stroke(colours.lotEdge, 0.5)}),
  road_areas: f => new ol.style.Style({fill: fill(f.get('surface') === 'sidewalk' ? colours.sidewalk : colours.carriageway)}),
  roads: () => new ol.style.Style({stroke: new ol.style.Stroke({color: '#fff', width: 1, lineDash: [4, 4]})}),
  buildings: () => new ol.style.Style({fill: fill(colours.building), stroke: stroke(colours.buildingEdge, 0.5)}),
};
// The legend: each layer's swatch beside its toggle, in the colours above (zones in the
// zone types' colours side by side; green blocks are parks).
const stripes = list => `linear-gradient(to right, ${list.map((c, i) => `${c} ${i * 100 / list.length}% ${(i + 1) * 100 / list.length}%`).join(', ')})`;
const swatches = {
  zones: stripes(Object.values(zoneColours).map(c => rgba(c, 0.6))),
  water: colours.water,
  blocks: stripes(['#fff0', colours.green]),
  lots: colours.lot,
  road_areas: stripes([colours.sidewalk, colours.carriageway, colours.sidewalk]),
  roads: `repeating-linear-gradient(to right, #fff 0 4px, ${colours.carriageway} 4px 8px)`,
  buildings: colours.building,
};

export class CityLayers {
  constructor(group) {
    this.group = group;
    this.layers = {};
    this.data = {};
  }

  // Fetches every layer and the report; resolves to the report.
  async load() {
    const names = Object.keys(layerStyles);
    const docs = await Promise.all(names.map(n => fetch(`/api/layers/${n}.geojson`, {cache: 'no-store'})
                                                 .then(r => (r.ok ? r.json() : null))));
    this.group.getLayers().clear();
    const toggles = document.getElementById('layer-toggles');
    toggles.innerHTML = '';
    names.forEach((name, i) => {
      if (!docs[i]) return;
      this.data[name] = docs[i];
      const layer = new ol.layer.Vector({source: new ol.source.Vector({features: geojson.readFeatures(docs[i])}),
                                         style: layerStyles[name], properties: {name}});
      this.layers[name] = layer;
      this.group.getLayers().push(layer);
      const label = document.createElement('label');
      label.innerHTML = `<input type="checkbox" checked data-layer="${name}"> <span class="swatch"></span> ` +
                        `${name.replace('_', ' ')} (${docs[i].features.length})`;
      label.querySelector('.swatch').style.background = swatches[name];
      label.querySelector('input').addEventListener('change', e => layer.setVisible(e.target.checked));
      toggles.appendChild(label);
    });
    const report = await fetch('/api/report', {cache: 'no-store'}).then(r => (r.ok ? r.json() : null));
    this.showReport(report);
    document.getElementById('layers-panel').hidden = false;
    return report;
  }

  showReport(report) {
    const box = document.getElementById('report');
    box.innerHTML = '';
    if (!report) return;
    const rows = Object.entries(report.counts || {}).filter(([, v]) => typeof v === "number").map(([k, v]) => [k.replace(/_/g, ' '), v]);
    const seconds = Object.values(report.timings_s || {}).reduce((a, b) => a + (typeof b === 'number' ? b : 0), 0);
    // The server's seconds to its answer (what the page shows written: the layers, the 3D
    // view's tiles), and for the whole update so far, validation included once it has run.
    if (typeof report.answer_s === 'number') rows.push(['answered in', `${report.answer_s.toFixed(1)} s`]);
    rows.push(['server time', `${seconds.toFixed(1)} s`]);
    // What this generation reused of the one before (the server keeps each region's plans).
    const reused = report.reused;
    if (reused) {
      const part = (c, what) => `${c.reused.toLocaleString('en')} of ${c.of.toLocaleString('en')} ${what}`;
      rows.push(['reused', [part(reused.region_plans, 'regions'), part(reused.block_plans, 'blocks'),
                            part(reused.lot_placements, 'lots'), part(reused.structure_meshes, 'meshes')].join(', ')]);
    }
    if (report.validation)
      rows.push(['valid', report.validation.under_way ? 'checking…' : report.validation.stopped ? 'not checked (stopped)'
                          : String(report.validation.valid ?? report.validation.ok ?? '')]);
    for (const [k, v] of rows) {
      const dt = document.createElement('dt'), dd = document.createElement('dd');
      dt.textContent = k;
      dd.textContent = typeof v === 'number' ? v.toLocaleString('en') : v;
      box.append(dt, dd);
    }
    // The notes the CLI prints after a generation (README, Outputs: report.json).
    const notes = document.getElementById('report-notes');
    notes.innerHTML = '';
    for (const z of report.empty_zones || []) {
      const li = document.createElement('li');
      li.textContent = `${z.grid_cell || `features[${z.feature}]`} (${z.zone}) got no lots: ${z.why}`;
      notes.appendChild(li);
    }
    for (const p of report.validation?.problems || []) {
      const li = document.createElement('li');
      li.textContent = `invalid output: ${p}`;
      notes.appendChild(li);
    }
  }
}

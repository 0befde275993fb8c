// The side panel: the selected feature's zone type or road class and width, and the sketch's
// settings (seed; per zone type its layout and parameters). Nothing is checked here: the
// server checks as the CLI does and its one-line message is shown (docs/sketch.md).
const layouts = ['growth', 'grammar', 'voronoi', 'streets'];
const settingZones = ['residential', 'commercial', 'industrial'];

export class SettingsPanel {
  // `apply(exacity)` sends the new settings; it resolves to true when the server took them.
  // `typo(what, why)` tells of a parameter box that is not JSON, and the parser's message.
  constructor({apply, featureEdited, typo}) {
    this.apply = apply;
    this.featureEdited = featureEdited;
    this.typo = typo;
    this.note = document.getElementById('settings-note');
    this.feature = null;
    this.zoneBox = document.getElementById('zone-settings');
    this.rows = {};
    for (const zone of settingZones) {
      const box = document.createElement('div');
      box.className = 'zone-setting';
      box.innerHTML = `<label>${zone} layout <select data-zone="${zone}">` +
        layouts.map(l => `<option>${l}</option>`).join('') + '</select></label>' +
        `<label>${zone} parameters (JSON)<textarea rows="2" data-zone="${zone}" spellcheck="false"></textarea></label>`;
      this.zoneBox.appendChild(box);
      this.rows[zone] = {layout: box.querySelector('select'), params: box.querySelector('textarea')};
    }
    this.seed = document.getElementById('seed');
    document.getElementById('apply-settings').addEventListener('click', () => this.applySettings());

    this.zoneType = document.getElementById('zone-type');
    this.roadClass = document.getElementById('road-class');
    this.roadWidth = document.getElementById('road-width');
    this.zoneType.addEventListener('change', () => this.editFeature({zone: this.zoneType.value}));
    this.roadClass.addEventListener('change', () => this.editFeature({road: this.roadClass.value}));
    this.roadWidth.addEventListener('change', () => this.editFeature({width: Number(this.roadWidth.value)}));
  }

  // Shows the sketch's "exacity" member.
  show(exacity) {
    this.current = exacity || {};
    this.note.textContent = '';
    this.seed.value = this.current.seed ?? 1;
    // The files the sketch names, which Models… and Heightmap… replace.
    document.getElementById('models-in-use').textContent = this.current.models ?? 'none (Models… loads one)';
    document.getElementById('heightmap-in-use').textContent = this.current.terrain?.heightmap ?? 'none (flat ground)';
    const zones = this.current.zones || {};
    for (const zone of settingZones) {
      const {layout, ...params} = zones[zone] || {};
      this.rows[zone].layout.value = layout || 'growth';
      this.rows[zone].params.value = Object.keys(params).length ? JSON.stringify(params) : '';
    }
  }

  // The sketch's settings kept as the base of the next Apply, the form left as typed: after
  // a refusal the typed text stays to be fixed.
  keep(exacity) {
    this.current = exacity || {};
  }

  // The settings as the form says, or null when a parameter box is not JSON: that one is
  // named with the place the parser stopped, and the cursor put there. JSON that is not an
  // object is sent as written, so the server's refusal names it.
  read() {
    const exacity = {...this.current, seed: this.seed.value === '' ? this.seed.value : Number(this.seed.value)};
    const zones = {...(this.current.zones || {})};
    for (const zone of settingZones) {
      const box = this.rows[zone].params;
      const text = box.value.trim();
      let params = {};
      if (text) {
        try {
          params = JSON.parse(text);
        } catch (x) {
          const at = Number(/position (\d+)/.exec(x.message)?.[1] ?? -1) + box.value.indexOf(text);
          box.focus();
          if (at >= box.value.indexOf(text)) box.setSelectionRange(at, at + 1);
          this.typo(`${zone} parameters are not JSON`, x.message);
          return null;
        }
      }
      const layout = this.rows[zone].layout.value;
      if (typeof params !== 'object' || Array.isArray(params) || params === null) zones[zone] = params;
      else if (layout === 'growth' && !Object.keys(params).length) delete zones[zone];
      else zones[zone] = layout === 'growth' && !('layout' in (this.current.zones?.[zone] || {})) ? params : {layout, ...params};
    }
    if (Object.keys(zones).length) exacity.zones = zones; else delete exacity.zones;
    return exacity;
  }

  async applySettings() {
    const exacity = this.read();
    this.note.textContent = exacity && (await this.apply(exacity)) ? '' : 'not applied';
  }

  // The selected feature's properties, or none.
  select(feature) {
    this.feature = feature;
    const panel = document.getElementById('feature-panel');
    panel.hidden = !feature;
    if (!feature) return;
    const zone = feature.get('zone'), road = feature.get('road');
    document.getElementById('zone-row').hidden = !zone;
    document.getElementById('road-row').hidden = !road;
    document.getElementById('width-row').hidden = !road;
    if (zone) this.zoneType.value = zone;
    if (road) {
      this.roadClass.value = road;
      this.roadWidth.value = feature.get('width') ?? '';
    }
  }

  editFeature(properties) {
    if (!this.feature) return;
    this.feature.setProperties(properties);
    this.featureEdited();
  }
}

// The side panel: the selected feature's zone type or road class and width, and the sketch's
// settings: the seed, and per zone type a form made from the settings table the CLI reads
// (GET /api/settings: each key's kind, bounds, default, unit and description), with the same
// settings as JSON in an advanced view. Nothing is checked here: the server checks as the CLI
// does, and a refusal's one line is shown next to the field it names.
const settingZones = ['residential', 'commercial', 'industrial'];

function element(tag, properties = {}, ...children) {
  const e = Object.assign(document.createElement(tag), properties);
  e.append(...children);
  return e;
}

// A field's input for one row of the table; `value` reads it (undefined: not set, so the
// default), `set` shows a value (undefined: none).
function field(row) {
  const shown = JSON.stringify(row.default);
  const number = (placeholder) => element('input', {type: 'number', placeholder: placeholder ?? '',
                                                    step: row.kind === 'whole' ? 1 : 'any', min: row.min, max: row.max});
  if (row.kind === 'number' || row.kind === 'whole') {
    const input = number(row.default);
    return {inputs: [input], value: () => (input.value === '' ? undefined : Number(input.value)),
            set: v => { input.value = typeof v === 'number' ? v : ''; }};
  }
  if (row.kind === 'range') {
    const low = number(row.default[0]), high = number(row.default[1]);
    return {inputs: [low, high],
            value: () => (low.value === '' && high.value === '' ? undefined :
                          [low.value === '' ? row.default[0] : Number(low.value), high.value === '' ? row.default[1] : Number(high.value)]),
            set: v => { low.value = Array.isArray(v) ? v[0] : ''; high.value = Array.isArray(v) ? v[1] : ''; }};
  }
  if (row.kind === 'choice' || row.kind === 'boolean') {
    const values = row.kind === 'choice' ? row.choices : [true, false];
    const select = element('select', {}, element('option', {value: '', textContent: `default (${row.default})`}),
                           ...values.map(v => element('option', {value: JSON.stringify(v), textContent: String(v)})));
    return {inputs: [select], value: () => (select.value === '' ? undefined : JSON.parse(select.value)),
            set: v => { select.value = v === undefined ? '' : JSON.stringify(v); }};
  }
  // A key its step reads itself (lists, file and channel names): JSON, or else a string.
  const input = element('input', {type: 'text', placeholder: shown === 'null' ? '' : shown, spellcheck: false});
  return {inputs: [input],
          value: () => {
            if (input.value.trim() === '') return undefined;
            try { return JSON.parse(input.value); } catch { return input.value; }
          },
          set: v => { input.value = v === undefined ? '' : typeof v === 'string' ? v : JSON.stringify(v); }};
}

export class SettingsPanel {
  // `apply(exacity)` sends the new settings; it resolves to the server's refusal message, or
  // null when it took them. `typo(what, why)` tells of a JSON box that is not JSON, and the
  // parser's message.
  constructor({apply, featureEdited, typo}) {
    this.apply = apply;
    this.featureEdited = featureEdited;
    this.typo = typo;
    this.note = document.getElementById('settings-note');
    this.feature = null;
    this.current = {};
    this.forms = {};  // per zone type, per key: its field and its error line
    this.boxes = {};  // per zone type, the advanced view's JSON box
    for (const zone of settingZones) {
      const box = element('textarea', {rows: 2, spellcheck: false});
      box.dataset.zone = zone;
      document.getElementById('zone-json').append(element('label', {}, `${zone} (JSON)`, box));
      this.boxes[zone] = box;
    }
    this.seed = document.getElementById('seed');
    this.seed.addEventListener('change', () => this.applySettings());
    document.getElementById('apply-settings').addEventListener('click', () => this.applySettings());

    this.zoneType = document.getElementById('zone-type');
    this.roadClass = document.getElementById('road-class');
    this.roadWidth = document.getElementById('road-width');
    this.zoneType.addEventListener('change', () => this.editFeature({zone: this.zoneType.value}));
    this.roadClass.addEventListener('change', () => this.editFeature({road: this.roadClass.value}));
    this.roadWidth.addEventListener('change', () => this.editFeature({width: Number(this.roadWidth.value)}));
  }

  // The forms, one per zone type, from the server's settings table.
  async build() {
    const table = await fetch('/api/settings', {cache: 'no-store'}).then(r => r.json());
    const holder = document.getElementById('zone-forms');
    for (const zone of settingZones) {
      const form = element('details', {className: 'zone-form'}, element('summary', {textContent: zone}));
      form.dataset.zone = zone;
      this.forms[zone] = {};
      for (const row of table.zones[zone]) {
        const f = field(row), error = element('p', {className: 'field-error'});
        const label = element('label', {title: row.description},
                              element('span', {className: 'key', textContent: row.key.replace(/_/g, ' ')}),
                              ...f.inputs, element('span', {className: 'unit', textContent: row.unit}));
        const line = element('div', {className: 'setting'}, label, element('p', {className: 'about', textContent: row.description}), error);
        line.dataset.key = row.key;
        for (const input of f.inputs) input.addEventListener('change', () => this.applyField(zone, row.key));
        form.append(line);
        this.forms[zone][row.key] = {...f, error, line};
      }
      holder.append(form);
    }
    this.show(this.current);
  }

  // Shows the sketch's "exacity" member.
  show(exacity) {
    this.current = exacity || {};
    this.note.textContent = '';
    this.seed.value = this.current.seed ?? 1;
    // The files the sketch names, which Models… and Heightmap… replace.
    document.getElementById('models-in-use').textContent = this.current.models ?? 'none (Models… loads one)';
    document.getElementById('heightmap-in-use').textContent = this.current.terrain?.heightmap ?? 'none (flat ground)';
    document.getElementById('like-in-use').textContent = this.current.like ?? 'no place (Like a place… loads one)';
    const zones = this.current.zones || {};
    for (const zone of settingZones) {
      const settings = zones[zone] && typeof zones[zone] === 'object' ? zones[zone] : {};
      this.boxes[zone].value = zones[zone] === undefined ? '' : JSON.stringify(zones[zone]);
      for (const [key, f] of Object.entries(this.forms[zone] || {})) {
        f.set(settings[key]);
        f.error.textContent = '';
        f.line.classList.toggle('set', key in settings);
        f.line.classList.remove('refused');
      }
    }
  }

  // The sketch's settings kept as the base of the next edit, the form left as typed: after
  // a refusal the typed text stays to be fixed.
  keep(exacity) {
    this.current = exacity || {};
  }

  // `zones` as the sketch's settings, a zone type with nothing set left out.
  withZones(zones) {
    const exacity = {...this.current};
    for (const zone of Object.keys(zones)) if (zones[zone] === undefined) delete zones[zone];
    if (Object.keys(zones).length) exacity.zones = zones; else delete exacity.zones;
    return exacity;
  }

  // One field changed: its zone type's settings as its form says, sent; a refusal's line
  // shown under the field it names (else under this one).
  async applyField(zone, key) {
    const settings = {};
    for (const [k, f] of Object.entries(this.forms[zone])) {
      const v = f.value();
      if (v !== undefined) settings[k] = v;
    }
    const exacity = this.withZones({...(this.current.zones || {}), [zone]: Object.keys(settings).length ? settings : undefined});
    const refusal = await this.apply(exacity);
    if (refusal === null) return;
    const named = new RegExp(`"exacity"\\.zones\\.${zone}\\.(\\w+)`).exec(refusal)?.[1];
    const f = this.forms[zone][named in this.forms[zone] ? named : key];
    f.error.textContent = refusal.replace(/^[^:]*: "exacity"\.zones\.\w+\.\w+: /, '');
    f.error.title = refusal;
    f.line.classList.add('refused');
  }

  // The settings as the seed and the JSON boxes say, or null when a box is not JSON: that one
  // is named with the place the parser stopped, and the cursor put there. JSON that is not
  // an object is sent as written, so the server's refusal names it.
  read() {
    const zones = {...(this.current.zones || {})};
    for (const zone of settingZones) {
      const box = this.boxes[zone];
      const text = box.value.trim();
      if (!text) {
        zones[zone] = undefined;
        continue;
      }
      try {
        zones[zone] = JSON.parse(text);
      } catch (x) {
        const at = Number(/position (\d+)/.exec(x.message)?.[1] ?? -1) + box.value.indexOf(text);
        box.focus();
        if (at >= box.value.indexOf(text)) box.setSelectionRange(at, at + 1);
        this.typo(`${zone} parameters are not JSON`, x.message);
        return null;
      }
    }
    const exacity = this.withZones(zones);
    exacity.seed = this.seed.value === '' ? this.seed.value : Number(this.seed.value);
    return exacity;
  }

  async applySettings() {
    const exacity = this.read();
    this.note.textContent = exacity && (await this.apply(exacity)) === null ? '' : 'not applied';
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

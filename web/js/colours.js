// The page's colours and the roads' default widths, as the program has them (GET /api/palette,
// generate/city/palette.h): the sketch's zones and roads, and the SVG map's colours for the
// generated layers; and the renderer's sun.
const palette = await fetch('/api/palette', {cache: 'no-store'}).then(r => r.json());
const bytes = hex => [1, 3, 5].map(i => parseInt(hex.slice(i, i + 2), 16));

export const zoneColours = Object.fromEntries(Object.entries(palette.sketch_zones).map(([zone, hex]) => [zone, bytes(hex)]));
export const roadColours = palette.sketch_roads;
export const defaultWidths = palette.road_widths;
export const mapColours = palette.map;
// The renderer's sun, for the 3D view's light and shadows.
export const sun = palette.sun;

export function rgba(rgb, alpha) { return `rgba(${rgb[0]}, ${rgb[1]}, ${rgb[2]}, ${alpha})`; }

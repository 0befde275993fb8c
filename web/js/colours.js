// Zone colours on the page: red residential, green commercial and brown industrial
// as drawn, with park and water as on the SVG map (generate/city/palette.h).
export const zoneColours = {
  residential: [214, 96, 77], commercial: [63, 154, 110], industrial: [150, 105, 60],
  park: [166, 217, 106], water: [91, 155, 213],
};
export const roadColours = {highway: '#111', main: '#333', local: '#555'};
export const defaultWidths = {highway: 24, main: 12, local: 8};

export function rgba(rgb, alpha) { return `rgba(${rgb[0]}, ${rgb[1]}, ${rgb[2]}, ${alpha})`; }

// Writes country outlines from the world-atlas package (Natural Earth 1:50m admin-0
// countries as TopoJSON) as SVG files: each country's rings as published, projected with
// d3-geo's Mercator fitted to a 1000-unit box, adaptive resampling off (precision 0), so
// every vertex is one of Natural Earth's; coordinates rounded to 0.01 unit.
//
// Usage (from a folder where `npm install world-atlas@2.0.2 topojson-client@3.1.0
// d3-geo@3.1.2` was run): node countries.mjs OUTDIR Name1 Name2 ...
import { readFileSync, writeFileSync, mkdirSync } from 'fs';
import { join } from 'path';
import { createRequire } from 'module';
import { pathToFileURL } from 'url';

// the packages are resolved from the current folder (where npm installed them)
const require = createRequire(join(process.cwd(), 'package.json'));
const topo = await import(pathToFileURL(require.resolve('topojson-client')));
const { geoMercator, geoPath } = await import(pathToFileURL(require.resolve('d3-geo')));

const [outDir, ...names] = process.argv.slice(2);
const atlas = JSON.parse(readFileSync('node_modules/world-atlas/countries-50m.json', 'utf8'));
const version = JSON.parse(readFileSync('node_modules/world-atlas/package.json', 'utf8')).version;
const countries = topo.feature(atlas, atlas.objects.countries).features;
mkdirSync(outDir, { recursive: true });
for (const name of names) {
  const f = countries.find((c) => c.properties.name === name);
  if (!f) throw new Error(`no country named ${name}`);
  const projection = geoMercator().precision(0).fitExtent([[0, 0], [1000, 1000]], f);
  const path = geoPath(projection).digits(2);
  const [[x0, y0], [x1, y1]] = path.bounds(f);
  const vb = [Math.floor(x0), Math.floor(y0), Math.ceil(x1 - Math.floor(x0)), Math.ceil(y1 - Math.floor(y0))];
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${vb.join(' ')}">
<!-- ${name}: Natural Earth 1:50m admin-0 countries via world-atlas ${version} (countries-50m.json), Mercator (d3-geo) -->
<path fill-rule="evenodd" d="${path(f)}"/>
</svg>
`;
  writeFileSync(join(outDir, name.toLowerCase().replace(/ /g, '-') + '.svg'), svg);
}

// Bundles the page viewer (src/viewer.js) with the parts of three.js it imports into one
// minified script: node build-viewer.mjs OUT.js. Run by the build (cmake/web_viewer.cmake); the
// library embeds OUT.js in every interactive page (docs/web-pages.md, "Bundling").
//
// One classic script (an IIFE) rather than ES modules from an import map: a page opened from
// file:// may not load module scripts from other files, data: URLs cannot import one another by
// relative path, and one script carries only the parts of three.js the viewer uses (tree
// shaking: about 0.64 MB instead of 2.3 MB for three.core.js, three.module.js and the add-ons).
import { build } from 'esbuild';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const out = process.argv[2];
if (!out) {
  console.error('usage: node build-viewer.mjs OUT.js');
  process.exit(2);
}
await build({
  entryPoints: [join(here, 'src', 'viewer.js')],
  absWorkingDir: here,
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  charset: 'ascii',
  legalComments: 'eof',
  alias: { 'three/addons': 'three/examples/jsm' },
  outfile: out,
  logLevel: 'warning',
});

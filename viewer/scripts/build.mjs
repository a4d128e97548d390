// Builds the viewer: one minified IIFE bundle (three.js, GLTFLoader, OrbitControls, our code and
// CSS) as OUT/viewer.js, and OUT/index.html loading it. OUT is $VIEWER_OUT_DIR, default dist/
// (relative paths are taken from the viewer directory).
import { build, transform } from 'esbuild';
import { mkdir, readFile, writeFile } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';

const here = dirname(dirname(fileURLToPath(import.meta.url)));
const out = resolve(here, process.env.VIEWER_OUT_DIR || 'dist');
const { version } = JSON.parse(await readFile(join(here, 'package.json'), 'utf8'));

await mkdir(out, { recursive: true });
const result = await build({
  entryPoints: [join(here, 'src', 'main.js')],
  bundle: true,
  format: 'iife',
  minify: true,
  target: ['es2020', 'chrome90', 'firefox90', 'safari15'],
  platform: 'browser',
  plugins: [
    {
      // CSS imported as minified text; main.js injects it as a <style> element.
      name: 'css-text',
      setup(b) {
        b.onLoad({ filter: /\.css$/ }, async (args) => {
          const { code } = await transform(await readFile(args.path, 'utf8'), { loader: 'css', minify: true });
          return { contents: code, loader: 'text' };
        });
      },
    },
  ],
  charset: 'ascii',
  legalComments: 'eof',
  banner: { js: `/* lang2manip viewer ${version} (three.js, MIT licence) */` },
  define: { 'process.env.NODE_ENV': '"production"' },
  write: false,
  metafile: true,
  logLevel: 'warning',
});

const code = result.outputFiles[0].text;
// The bundle is inlined into <script> elements of self-contained pages: text that would end or
// disturb the script element there must not occur.
for (const forbidden of [/<\/script/i, /<!--/, /<script/i]) {
  const match = forbidden.exec(code);
  if (match) {
    console.error(`build: viewer.js contains ${JSON.stringify(match[0])} at offset ${match.index}: it cannot be inlined into an HTML page`);
    process.exit(1);
  }
}
await writeFile(join(out, 'viewer.js'), code);
await writeFile(
  join(out, 'index.html'),
  `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>lang2manip viewer</title>
<link rel="icon" href="data:,">
</head>
<body>
<script src="viewer.js"></script>
</body>
</html>
`,
);

const bytes = Buffer.byteLength(code);
const gzip = gzipSync(code).length;
console.log(`build: ${join(out, 'viewer.js')} ${(bytes / 1024).toFixed(1)} KiB (${(gzip / 1024).toFixed(1)} KiB gzip), ${join(out, 'index.html')}`);
if (process.env.VIEWER_BUNDLE_REPORT) {
  const inputs = Object.entries(result.metafile.outputs)[0][1].inputs;
  for (const [path, info] of Object.entries(inputs).sort((a, b) => b[1].bytesInOutput - a[1].bytesInOutput).slice(0, 15)) {
    console.log(`  ${(info.bytesInOutput / 1024).toFixed(1).padStart(7)} KiB  ${path}`);
  }
}

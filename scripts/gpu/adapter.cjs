// exits 1 when Dawn finds no adapter, else prints it
const { create, globals } = require('webgpu');
Object.assign(globalThis, globals);
const g = create([]);
globalThis.keep = g;
g.requestAdapter({ powerPreference: 'high-performance' }).then((a) => {
  if (!a) { console.log('no adapter'); process.exit(1); }
  console.log('adapter:', a.info.vendor, a.info.architecture, a.info.description);
});

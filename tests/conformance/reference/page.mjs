// The suite's scene in three.js with three-vrm's MToon (see ../README.md, "The scene"): a 512 x 512 picture,
// 4x MSAA, sRGB output, no tone mapping, on white.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { VRMLoaderPlugin } from '@pixiv/three-vrm';

const SIZE = 512;
const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true, alpha: false });
renderer.setPixelRatio(1);
renderer.setSize(SIZE, SIZE, false);
renderer.outputColorSpace = THREE.SRGBColorSpace;
renderer.toneMapping = THREE.NoToneMapping;
renderer.setClearColor(0xffffff, 1);

const scene = new THREE.Scene();
// Linear RGB 0.3 at intensity 0.5: irradiance 0.15, so MToon's indirect term is 0.15 / pi x the lit colour.
scene.add(new THREE.AmbientLight(new THREE.Color(0.3, 0.3, 0.3), 0.5));
// Intensity pi: three-vrm's lit colour is lightColor x BRDF_Lambert(colour) = colour on the lit side.
const sun = new THREE.DirectionalLight(0xffffff, Math.PI);
sun.position.set(0.3, 0.6, 0.7); // the light travels along (-0.3, -0.6, -0.7), toward its target at the origin
scene.add(sun);
scene.add(sun.target);

const camera = new THREE.PerspectiveCamera(30, 1, 0.1, 20);
const EYES = { front: [0, 1.4, 1.5], back: [0, 1.4, -1.5] };

const loader = new GLTFLoader();
loader.register((parser) => new VRMLoaderPlugin(parser));

function dispose(root) {
  root.traverse((object) => {
    if (object.geometry) object.geometry.dispose();
    const materials = Array.isArray(object.material) ? object.material : object.material ? [object.material] : [];
    for (const material of materials) {
      for (const value of Object.values(material)) {
        if (value && value.isTexture) value.dispose();
      }
      material.dispose();
    }
  });
}

// Renders one case: the file at `url` from `view` ('front' or 'back'), its MToon UV animation advanced by
// `time` seconds; returns the picture as a PNG data URL.
window.renderCase = async (url, view, time) => {
  const gltf = await loader.loadAsync(url);
  scene.add(gltf.scene);
  gltf.scene.traverse((object) => {
    const materials = Array.isArray(object.material) ? object.material : object.material ? [object.material] : [];
    for (const material of materials) {
      // update() also uploads the uniforms three-vrm sets outside three.js' own (opacity, texture transforms)
      if (material.isMToonMaterial) material.update(time);
    }
  });
  camera.position.set(...EYES[view]);
  camera.up.set(0, 1, 0);
  camera.lookAt(0, 1.4, 0);
  camera.updateProjectionMatrix();
  renderer.render(scene, camera);
  const png = canvas.toDataURL('image/png');
  scene.remove(gltf.scene);
  dispose(gltf.scene);
  return png;
};

window.versions = () => {
  const gl = renderer.getContext();
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return {
    three: THREE.REVISION,
    webglVersion: gl.getParameter(gl.VERSION),
    webglRenderer: info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
    samples: gl.getParameter(gl.SAMPLES),
  };
};

window.pageReady = true;

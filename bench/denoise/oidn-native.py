"""Our denoiser against Intel's native Open Image Denoise (pyoidn, OIDN 2.5)
on the same buffers: relMSE against the Mitsuba reference of the plain
render, and of OIDN's balanced and high-quality filters, with the auxiliary
images as given (prefiltered by OIDN) and as clean (clean_aux).

  pip install pyoidn
  for s in seed glossy small-light envmap; do
    npx pathtrace render test/fixtures/scenes/$s.json --spp 16 --seed 1 -o /tmp/dn/$s.png \
      --hdr /tmp/dn/$s.pfm --aov /tmp/dn/$s-alb.pfm,/tmp/dn/$s-nrm.pfm
  done
  python3 bench/denoise/oidn-native.py /tmp/dn seed glossy small-light envmap
"""
import sys

import numpy as np
import pyoidn


def read_pfm(path):
    with open(path, 'rb') as f:
        if f.readline().strip() != b'PF':
            raise ValueError(f'{path}: not a colour PFM')
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4').reshape(height, width, 3)
    return np.flipud(data).astype(np.float32).copy()


def rel_mse(image, reference):
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 0.01)))


def main(folder, scenes):
    print('| scene | plain | OIDN balanced | balanced, clean aux | OIDN high | high, clean aux |')
    print('| --- | --- | --- | --- | --- | --- |')
    for scene in scenes:
        color = read_pfm(f'{folder}/{scene}.pfm')
        albedo = read_pfm(f'{folder}/{scene}-alb.pfm')
        normal = read_pfm(f'{folder}/{scene}-nrm.pfm')
        reference = read_pfm(f'test/fixtures/references/{scene}.pfm')
        cells = [rel_mse(color, reference)]
        for quality in ['balanced', 'high']:
            for clean in [False, True]:
                out = pyoidn.denoise(color, albedo, normal, hdr=True, clean_aux=clean, quality=quality)
                cells.append(rel_mse(out, reference))
        print(f'| {scene} | ' + ' | '.join(f'{c:.3e}' for c in cells) + ' |')


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2:])

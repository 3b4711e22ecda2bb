#!/usr/bin/env python3
"""How noisy is equal_time.py's reference? Two 60 s BDPT renders of the droplet with different
seeds, compared with each other over the image and over the caustic crop (docs/python.md).

    PYTHONPATH=build-release/python python3 python/examples/reference_noise.py
"""
import os

import snell
s = snell.load_file(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scenes', 'droplet', 'droplet.xml'), res_x=320, res_y=240)
it = {'type': 'bdpt', 'max_depth': 12, 'spectral_samples': 4}
a = s.render(integrator=it, time=60, seed=1)
b = s.render(integrator=it, time=60, seed=2)
crop = [115, 95, 95, 55]
for name, c in (('image', None), ('caustic', crop)):
    m = snell.diff(a, b, crop=c)
    print(name, 'spp', a.stats['spp_reached'], b.stats['spp_reached'], 'median', m['median_rel_error'], 'relMSE', m['rel_mse'])

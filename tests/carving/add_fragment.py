"""Paints a disc of the seed's own colour (the pixel at the image centre, where the rendered seed
lies) into one view of a rendered seed: a second object in the silhouette image, as a broken-off
piece or a neighbouring grain would be.
    add_fragment.py VIEW.png RADIUS_PX"""
import sys

import matplotlib.image as mpimg
import numpy as np

path, radius = sys.argv[1], float(sys.argv[2])
img = mpimg.imread(path)
h, w = img.shape[:2]
colour = img[h // 2, w // 2].copy()
yy, xx = np.mgrid[0:h, 0:w]
cx, cy = radius + 10, radius + 10  # the top-left corner, clear of the seed and the frame
img[(xx - cx) ** 2 + (yy - cy) ** 2 <= radius ** 2] = colour
mpimg.imsave(path, img)

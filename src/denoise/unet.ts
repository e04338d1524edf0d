/**
 * OIDN's U-Net ("rt" filter, default and small sizes share this graph; only
 * the channel counts differ, read from the weights) on TensorFlow.js.
 * Every convolution is 3x3, stride 1, "same" padding, ReLU except the last;
 * pooling is 2x2 max; upsampling is nearest x2. Layer names are OIDN's.
 */
import * as tf from '@tensorflow/tfjs-core';
import { WeightsError, type WeightTensor } from './tza';

/** The encoder's four poolings: the input must be a multiple of this in both dimensions. */
export const UNET_ALIGNMENT = 16;
/** Input channels: colour, albedo, normal (3 each). */
export const UNET_INPUT_CHANNELS = 9;

const CONVOLUTIONS = [
  'enc_conv0', 'enc_conv1', 'enc_conv2', 'enc_conv3', 'enc_conv4', 'enc_conv5a', 'enc_conv5b',
  'dec_conv4a', 'dec_conv4b', 'dec_conv3a', 'dec_conv3b', 'dec_conv2a', 'dec_conv2b',
  'dec_conv1a', 'dec_conv1b', 'dec_conv0',
] as const;
type ConvName = (typeof CONVOLUTIONS)[number];

interface ConvWeights {
  filter: tf.Tensor4D;
  bias: tf.Tensor1D;
}

export class UNet {
  private readonly convs: Map<ConvName, ConvWeights>;

  constructor(weights: Map<string, WeightTensor>) {
    this.convs = new Map(CONVOLUTIONS.map((name) => [name, uploadConv(weights, name)]));
    const inputChannels = this.convs.get('enc_conv0')!.filter.shape[2];
    if (inputChannels !== UNET_INPUT_CHANNELS) {
      throw new WeightsError(`enc_conv0 takes ${inputChannels} channels; colour + albedo + normal weights (9) are needed`);
    }
  }

  /** input: [1, H, W, 9] with H, W multiples of UNET_ALIGNMENT; returns [1, H, W, 3]. */
  run(input: tf.Tensor4D): tf.Tensor4D {
    return tf.tidy(() => {
      const conv = (name: ConvName, x: tf.Tensor4D, relu = true) => {
        const { filter, bias } = this.convs.get(name)!;
        return tf.fused.conv2d({ x, filter, bias, strides: 1, pad: 'same', activation: relu ? 'relu' : 'linear' });
      };
      const pool = (x: tf.Tensor4D) => tf.maxPool(x, 2, 2, 'same');
      const up = (x: tf.Tensor4D) => tf.image.resizeNearestNeighbor(x, [x.shape[1] * 2, x.shape[2] * 2]);
      const pool1 = pool(conv('enc_conv1', conv('enc_conv0', input)));
      const pool2 = pool(conv('enc_conv2', pool1));
      const pool3 = pool(conv('enc_conv3', pool2));
      const pool4 = pool(conv('enc_conv4', pool3));
      let x = conv('enc_conv5b', conv('enc_conv5a', pool4));
      x = conv('dec_conv4b', conv('dec_conv4a', tf.concat([up(x), pool3], 3)));
      x = conv('dec_conv3b', conv('dec_conv3a', tf.concat([up(x), pool2], 3)));
      x = conv('dec_conv2b', conv('dec_conv2a', tf.concat([up(x), pool1], 3)));
      x = conv('dec_conv1b', conv('dec_conv1a', tf.concat([up(x), input], 3)));
      return conv('dec_conv0', x, false);
    });
  }

  dispose(): void {
    for (const { filter, bias } of this.convs.values()) {
      filter.dispose();
      bias.dispose();
    }
  }
}

function uploadConv(weights: Map<string, WeightTensor>, name: ConvName): ConvWeights {
  const weight = weights.get(`${name}.weight`);
  const bias = weights.get(`${name}.bias`);
  if (!weight || !bias) throw new WeightsError(`missing tensor ${name}.${weight ? 'bias' : 'weight'} (not an OIDN U-Net?)`);
  const [o, i, h, w] = weight.dims;
  if (weight.dims.length !== 4 || h !== 3 || w !== 3 || weight.layout !== 'oihw') {
    throw new WeightsError(`${name}.weight: expected a 3x3 OIHW kernel, got dims [${weight.dims}] layout ${weight.layout}`);
  }
  if (bias.dims.length !== 1 || bias.dims[0] !== o) throw new WeightsError(`${name}.bias: expected ${o} values, got [${bias.dims}]`);
  return tf.tidy(() => ({
    // OIHW (OIDN) -> HWIO (TensorFlow)
    filter: tf.transpose(tf.tensor4d(weight.data, [o, i, h, w]), [2, 3, 1, 0]),
    bias: tf.tensor1d(bias.data),
  }));
}
